"""The one picture reader (tilesolve.io.images.read_rgba): RGBA arrays and one-line errors, read
by the stipple, recursive-Wang and texture commands alike."""

from __future__ import annotations

import numpy as np
import pytest
from clitools import one_line_error, run
from PIL import Image

from tilesolve.errors import InvalidProblem
from tilesolve.io.images import read_rgba


def test_pictures_are_rgba_rows_from_the_top(tmp_path):
    a = np.zeros((2, 3), np.uint8)
    a[0, 2] = 200
    Image.fromarray(a, "L").save(tmp_path / "g.png")
    rgba = read_rgba(tmp_path / "g.png")
    assert rgba.shape == (2, 3, 4) and rgba.dtype == np.uint8
    assert rgba[0, 2].tolist() == [200, 200, 200, 255] and rgba[1, 2].tolist() == [0, 0, 0, 255]
    assert read_rgba(str(tmp_path / "g.png"), max_pixels=6).shape == (2, 3, 4)


@pytest.mark.parametrize("name, words", [
    ("missing.png", "missing.png: no such file"),
    ("adir", "adir: is a directory, not an image"),
    ("text.png", "text.png: not a readable image (cannot identify image file"),
    ("big.png", "big.png: the image has 12 pixels; at most 11"),
])
def test_unreadable_pictures_are_one_line_errors(tmp_path, name, words):
    (tmp_path / "adir").mkdir()
    (tmp_path / "text.png").write_text("this is no picture\n")
    Image.new("RGB", (4, 3)).save(tmp_path / "big.png")
    with pytest.raises(InvalidProblem) as err:
        read_rgba(tmp_path / name, max_pixels=11)
    message = str(err.value)
    assert message.startswith(f"{tmp_path / words}") and "\n" not in message, message
    assert message.count("not a readable image") == words.count("not a readable image"), message  # not wrapped


def test_a_decompression_bomb_is_refused(tmp_path, monkeypatch):
    Image.new("L", (20, 20)).save(tmp_path / "bomb.png")
    monkeypatch.setattr(Image, "MAX_IMAGE_PIXELS", 100)  # 400 pixels: over twice Pillow's limit
    with pytest.raises(InvalidProblem, match="bomb.png: the image has more pixels than Pillow's safety limit"):
        read_rgba(tmp_path / "bomb.png")


@pytest.mark.parametrize("command", [
    ["sample", "stipple", "missing.png", "--points", "100", "-o", "out.svg"],
    ["sample", "stipple", "missing.png", "--points", "100", "-o", "out.json"],
])
def test_a_missing_picture_through_the_console_script(tmp_path, command):
    assert one_line_error(run(*command, cwd=tmp_path)) == "tilesolve: error: missing.png: no such file"
    assert list(tmp_path.iterdir()) == []

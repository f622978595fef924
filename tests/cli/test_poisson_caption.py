"""The caption of ``tilesolve sample poisson-tiles window --svg``: the relative radius the window
achieved (eq. 4.1-4.3, class notes §4.2), measured on its points, beside the one the set asked
for. Through the console script."""

from __future__ import annotations

import json
import re

import numpy as np
import pytest
from clitools import run

from tilesolve.verify.poisson import relative_radius


@pytest.mark.slow
def test_the_window_caption_gives_the_achieved_rho_of_the_written_points(tmp_path):
    r = run("sample", "poisson-tiles", "build", "-C", "1", "-N", "16", "--rho", "0.75", "--seed", "1",
            "-o", "set.json", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    r = run("sample", "poisson-tiles", "window", "set.json", "--region", "-2,3,4x3", "--seed", "2",
            "-o", "pts.json", "--svg", "pts.svg", cwd=tmp_path)
    assert r.returncode == 0, r.stderr
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", (tmp_path / "pts.svg").read_text())
    assert len(texts) == 1, texts
    found = re.search(r"rho = (\d\.\d{3}) achieved \(([\d.]+) asked\)", texts[0])
    assert found, texts[0]
    doc = json.loads((tmp_path / "pts.json").read_text())
    local = np.asarray(doc["local"], dtype=np.float64)  # relative to the window's SW corner
    win = doc["window"]
    achieved = relative_radius(local, win["width"] * win["height"])
    assert found.group(1) == f"{achieved:.3f}"
    assert float(found.group(2)) == doc["rho"] == 0.75
    # this window shows the difference: its least gap is wider than the set's distance
    assert found.group(1) != "0.750"
    assert texts[0].startswith(f"{len(local):,} points, ")

"""Screenshots of the studio compared with committed references (Playwright, headless Chromium).

One screenshot per family (the picture of a fixed problem and seed, opened from a shared link)
and per state of the page (cancelled, an invalid field, the infinite view), each compared
with its reference in ``tests/studio/screenshots/`` within a tolerance: both images are
shrunk 4 times (box filter) before they are compared, so that font hinting and antialiasing do
not count, and at most :data:`MOVED` of the shrunk pixels may differ by more than
:data:`STEP` in a channel, with a mean difference of at most :data:`MEAN`. A mismatch saves
the screenshot and the difference beside it in ``tests/artifacts/studio/``.

Regenerate the references after a deliberate change of the page or the pictures::

    TILESOLVE_UPDATE_SCREENSHOTS=1 python -m pytest -q tests/studio/test_screenshots.py

then look at ``tests/studio/screenshots/*.png`` before committing them.
"""

from __future__ import annotations

import io
import json
import os
import urllib.parse
from pathlib import Path

import numpy as np
import pytest
from PIL import Image, ImageChops

from tests.studio.browsing import cancel_a_long_search, fill, pick

REFERENCES = Path(__file__).resolve().parent / "screenshots"
ARTIFACTS = Path(__file__).resolve().parents[1] / "artifacts" / "studio"
UPDATE = os.environ.get("TILESOLVE_UPDATE_SCREENSHOTS") == "1"
#: Largest share of (shrunk) pixels that may differ by more than STEP.
MOVED = 0.01
#: A channel difference that counts as a changed pixel.
STEP = 48
#: Largest mean channel difference.
MEAN = 3.0
#: Every test here drives Chromium: slow.
pytestmark = pytest.mark.slow

#: One problem per family, with its seed: what its screenshot shows.
PROBLEMS = {
    "dappled": {"size": "24x16", "cond": "H0=2, V1=2"},
    "board": {"size": "24x16", "max_h": 4, "max_v": 4},
    "packing": {"kind": "corner", "colors": 2},
    "stochastic": {"kind": "corner", "size": "32x20"},
    "aperiodic": {},
    "aperiodic-window": {"builtin": "kari-culik-13", "size": "24x12"},
    "substitution": {"kind": "p3"},
    # a tiling with one solution: a SAT solver's choice among many would change with the encoding
    "shapes": {"grid": "omino", "shape": "XX/XX", "where": "region", "size": "6x4"},
    "isohedral": {"region": "6x4", "scale": 30},
    "poisson": {"size": "8x6"},
    "poisson-sphere": {},
    "recursive-wang": {},
    "stipple": {"image": "gradient", "points": 2000},
}


def shrunk(img: Image.Image) -> np.ndarray:
    img = img.convert("RGB")
    return np.asarray(img.resize((max(1, img.width // 4), max(1, img.height // 4)), Image.BOX), dtype=np.int16)


def compare(name: str, png: bytes) -> None:
    """Compare a screenshot with its reference (or write the reference with UPDATE)."""
    ref = REFERENCES / f"{name}.png"
    shot = Image.open(io.BytesIO(png))
    if UPDATE:
        REFERENCES.mkdir(exist_ok=True)
        shot.save(ref, optimize=True)
        return
    assert ref.exists(), f"no reference {ref.name}: regenerate them (module docstring)"
    want = Image.open(ref)
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    if shot.size != want.size:
        shot.save(ARTIFACTS / f"{name}-got.png")
        pytest.fail(f"{name}: screenshot {shot.size} but reference {want.size} (saved {name}-got.png)")
    a, b = shrunk(shot), shrunk(want)
    diff = np.abs(a - b)
    moved, mean = float((diff.max(axis=2) > STEP).mean()), float(diff.mean())
    if moved > MOVED or mean > MEAN:
        shot.save(ARTIFACTS / f"{name}-got.png")
        ImageChops.difference(shot.convert("RGB"), want.convert("RGB")).save(ARTIFACTS / f"{name}-diff.png")
        pytest.fail(f"{name}: {moved:.2%} of pixels moved (at most {MOVED:.0%}), mean difference {mean:.2f} "
                    f"(at most {MEAN}); see tests/artifacts/studio/{name}-got.png and -diff.png")


def open_link(page, server: str, fam: str, values: dict, seed: int = 1) -> dict:
    """Open the shared link of a solved problem and wait for its picture."""
    state = {"f": fam, "v": dict(values, seed=seed), "m": "auto", "go": 1}
    page.goto("about:blank")  # a new document: the link is read as the page starts
    page.goto(server + "/#" + urllib.parse.urlencode({"s": json.dumps(state)}))
    page.wait_for_selector("body[data-ready='1']", timeout=120_000)
    page.wait_for_function("studio.result !== null && studio.job === null", timeout=120_000)
    return page.evaluate("studio.result")


@pytest.mark.parametrize("fam", sorted(PROBLEMS))
def test_each_familys_picture(page, server, fam):
    res = open_link(page, server, fam, PROBLEMS[fam])
    assert res["status"] == "sat" and res["seed"] == 1
    compare(f"family-{fam}", page.locator("#stage").screenshot(animations="disabled"))


def test_every_family_with_a_form_has_a_screenshot(page):
    listed = page.evaluate("studio.families.map(f => f.name)")
    assert sorted(listed) == sorted(PROBLEMS)


def test_the_cancelled_state(page):
    pick(page, "packing")
    cancel_a_long_search(page)
    compare("state-cancelled", page.locator("#stage").screenshot(animations="disabled"))


def test_the_invalid_state(page):
    pick(page, "dappled")
    fill(page, "cond", "H0=x")
    page.wait_for_function("document.getElementById('describe').dataset.state === 'invalid'")
    page.locator("#describe").evaluate("el => el.scrollIntoView()")
    compare("state-invalid", page.locator("#panel section").first.screenshot(animations="disabled"))


def test_the_infinite_view(page):
    pick(page, "stochastic")
    page.fill("#seed", "2")  # the view's tiling is the seed's
    page.dispatch_event("#seed", "change")
    page.locator("#viewport").scroll_into_view_if_needed()
    page.wait_for_function("studio.view.wanted && studio.view.missing === 0 && studio.view.inflight === 0",
                           timeout=60_000)
    compare("state-view", page.locator("#viewport").screenshot(animations="disabled"))

"""The corner-tile atlas's synthesis (class notes §5.3): the graph cut of the new patch."""

from __future__ import annotations

import numpy as np

from tilesolve.gpu.texture import _cut_regions, graph_cut


def test_the_cut_runs_where_the_patches_agree_and_keeps_the_border():
    t = 32
    keep, cover = _cut_regions(t)
    rng = np.random.default_rng(5)
    old = rng.integers(0, 256, (t, t, 4)).astype(np.float32)
    new = rng.integers(0, 256, (t, t, 4)).astype(np.float32)
    yy, xx = np.mgrid[0:t, 0:t] + 0.5
    ring = np.abs(np.hypot(yy - t / 2, xx - t / 2) - 11) < 1.0  # the two patches agree on a ring of radius 11
    new[ring] = old[ring]
    inside = graph_cut(old, new, keep, cover)
    assert inside[cover].all() and not inside[keep].any()
    radius = np.hypot(yy - t / 2, xx - t / 2)
    # cut along the ring, and around the ends of the cross it must cover
    assert inside[radius < 10].all() and not inside[(radius > 12) & ~cover].any()
    assert np.array_equal(graph_cut(old, new, keep, cover), inside)  # the same cut every time

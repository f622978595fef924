"""Counting all C = 2 packings (class notes §5.5.3: 32 corner, 203,520 Wang; 1 fundamental corner)."""

from __future__ import annotations

import numpy as np
import pytest

from tilesolve.families import packing as facade
from tilesolve.constructive.packing_count import (
    PUBLISHED_COUNTS,
    count_packings,
    enumerate_packings,
    packing_orbits,
    symmetry_maps,
)
from tilesolve.constructive.packing import apply_symmetry
from tilesolve.encodings.packing import encode_packing
from tilesolve.engine.sat import count_models
from tilesolve.deadline import Deadline
from tilesolve.errors import InvalidProblem
from tilesolve.model.packing import PackingProblem
from tilesolve.verify.packing import is_packing


@pytest.mark.slow
def test_published_totals():
    assert facade.count(PackingProblem("corner", 2)).value == PUBLISHED_COUNTS[("corner", 2)][0] == 32
    assert facade.count(PackingProblem("wang", 2)).value == PUBLISHED_COUNTS[("wang", 2)][0] == 203_520
    # "The 32 solutions of the 2 color corner tile packing problem reduce to a single fundamental solution."
    assert facade.count(PackingProblem("corner", 2), up_to_symmetry=True).value == 1


@pytest.mark.slow
def test_wang_up_to_symmetry_agrees_with_burnside():
    """Orbits by canonical forms (911) equal the Burnside average of fixed points over the group
    of translations x rotations/reflections x colour permutations (16 * 8 * 2 = 256 elements)."""
    res = facade.count(PackingProblem("wang", 2), up_to_symmetry=True)
    assert res.exact and res.value == 911
    anchored = np.asarray(list(enumerate_packings("wang", 2)), dtype=np.int8)
    allp = np.concatenate([np.roll(anchored, (r, c), axis=(1, 2)) for r in range(4) for c in range(4)])
    assert len(allp) == 203_520
    fixed = 0
    group = 0
    for _, turns, mirrored, m in symmetry_maps("wang", 2):
        g = allp[:, :, ::-1] if mirrored else allp
        g = m.astype(np.int8)[np.rot90(g, k=-turns, axes=(1, 2))]
        for r in range(4):
            for c in range(4):
                fixed += int((np.roll(g, (r, c), axis=(1, 2)) == allp).all(axis=(1, 2)).sum())
                group += 1
    assert group == 256
    assert fixed % group == 0 and fixed // group == 911


@pytest.mark.slow
def test_every_enumerated_packing_verifies_and_is_distinct():
    for kind in ("corner", "wang"):
        seen = set()
        for g in enumerate_packings(kind, 2):
            assert g[0, 0] == 0
            assert is_packing(PackingProblem(kind, 2), g)
            seen.add(g.tobytes())
        assert len(seen) == {"corner": 2, "wang": 12_720}[kind]


def test_corner_count_agrees_with_sat_enumeration():
    """Independent route: all models of the CNF without symmetry breaking (projected on placements)."""
    enc = encode_packing(PackingProblem("corner", 2), anchor_tile=None)
    res = count_models(enc.clauses, list(range(1, enc.n_placements + 1)))
    assert res.exact and res.value == 32


def test_orbit_representatives_are_packings():
    reps = packing_orbits(enumerate_packings("corner", 2), "corner", 2)
    assert len(reps) == 1 and is_packing(PackingProblem("corner", 2), reps[0])
    # every symmetry image of the representative is again a packing
    for _, turns, mirrored, m in symmetry_maps("corner", 2):
        assert is_packing(PackingProblem("corner", 2), apply_symmetry(reps[0], turns, mirrored, m, (1, 2)))


def test_time_limit_gives_unknown():
    res = count_packings("wang", 2, deadline=Deadline(1e-9))
    assert not res.exact and res.value is None and "time limit" in res.note


def test_counting_beyond_c2_refused():
    with pytest.raises(InvalidProblem, match="C=2"):
        facade.count(PackingProblem("corner", 3))
    with pytest.raises(InvalidProblem, match="kind"):
        facade.count(PackingProblem("hex", 2))

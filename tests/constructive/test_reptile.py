"""Rep-tile substitution (tilesolve.constructive.reptile): the rules found by exact cover, and
patches that cover 2^n P exactly (checked by the independent verifier)."""

import numpy as np
import pytest

from tilesolve.constructive import reptile as R
from tilesolve.verify.substitution import PROTOTILE_OUTLINES, reptile_violations


@pytest.mark.parametrize("name", sorted(R.PROTOTILES))
def test_every_builtin_tile_is_a_rep_tile_of_scale_two(name):
    assert len(R.rule(name)) == 4
    # the generator's outline (from cells) is the verifier's transcribed outline
    assert R.outline(R.PROTOTILES[name]).tolist() == [list(p) for p in PROTOTILE_OUTLINES[name][1]]


@pytest.mark.parametrize("name", sorted(R.PROTOTILES))
@pytest.mark.parametrize("steps", [0, 1, 3, 5])
def test_patches_cover_the_scaled_tile_exactly(name, steps):
    v = R.tiles(name, steps)
    assert len(v) == 4**steps and v.dtype == np.int64
    assert reptile_violations(name, steps, v) == []


def test_the_chair_rule_keeps_a_centre_chair_upright():
    """The classic chair substitution: one of the four chairs is the parent's orientation, at its centre."""
    maps = R.rule("chair")
    assert any(np.array_equal(g, np.eye(2)) and np.array_equal(t, [1, 1]) for g, t in maps)


def test_triangle_coordinates():
    assert np.allclose(R.lattice_xy("triangle", np.array([[1, 0], [0, 1]])), [[1, 0], [0.5, 3**0.5 / 2]])

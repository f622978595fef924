"""The dappled problem model: parsing, validation, refusal of absurd sizes."""

import numpy as np
import pytest

from tilesolve.errors import InvalidProblem
from tilesolve.model import Condition, DappledProblem, parse_condition, parse_count, parse_size


def test_parse_forms():
    assert str(parse_condition("h0=2")) == "H0=2"
    assert str(parse_condition("V{2,0}=3")) == "V{0,2}=3"
    assert parse_condition("V1=inf").limit is None
    assert (parse_count("1=8").low, parse_count("1=8").high) == (8, 8)
    assert (parse_count("1=4..").low, parse_count("1=4..").high) == (4, None)
    assert (parse_count("0=..5").low, parse_count("0=..5").high) == (0, 5)
    assert parse_size("64x48") == (48, 64)


@pytest.mark.parametrize("size", ["0x5", "5x0", "-3x4", "5", "axb", "100000x100000"])
def test_bad_sizes_are_refused_with_a_message(size):
    with pytest.raises(InvalidProblem) as e:
        parse_size(size)
    assert "\n" not in str(e.value)


def test_absurd_size_names_the_memory_it_would_need():
    with pytest.raises(InvalidProblem, match="GiB"):
        parse_size("100000x100000")


def test_validation():
    with pytest.raises(InvalidProblem, match="at least 2 tiles"):
        DappledProblem(2, 2, n_tiles=1)
    with pytest.raises(InvalidProblem, match="names tile 3"):
        DappledProblem(2, 2, conditions=[parse_condition("H3=2")])
    with pytest.raises(InvalidProblem, match="grid is 3x2"):
        DappledProblem(2, 3, fixed=np.zeros((3, 2), dtype=int))
    with pytest.raises(InvalidProblem, match="names tile 2"):
        DappledProblem(2, 2, fixed=np.array([[0, 2], [-1, -1]]))
    with pytest.raises(InvalidProblem, match="shape"):
        DappledProblem(2, 2, conditions=[Condition("H", (0,), np.ones((3, 3), dtype=int))])
    with pytest.raises(InvalidProblem):
        DappledProblem.from_strings("2x2", [], counts=["1=9"])


def test_single_tile_limits_combine_to_the_tightest():
    p = DappledProblem.from_strings("3x2", ["H0=3", "H0=2", "V1=4"])
    hp, vq = p.single_tile_limits()
    assert hp.shape == (2, 2, 3)
    assert (hp[0] == 2).all() and (hp[1] == 0).all() and (vq[1] == 4).all()
    assert DappledProblem.from_strings("3x2", ["H{0,1}=3"]).single_tile_limits() is None

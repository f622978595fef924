"""Forms (tilesolve.family.forms): when a field applies (Field.when), and what a field that does
not apply takes."""

from __future__ import annotations

import pytest

from tilesolve import family
from tilesolve.family import Field, Form

FORM = Form(
    fields=(
        Field("question", "choice", "question", "tile", choices=("tile", "heesch")),
        Field("size", "size", "size", "4x4", when=({"question": ("tile",)},)),
        Field("level", "int", "level", 3, low=1, high=6, when=({"question": ("heesch",)},)),
        Field("either", "int", "either", 1, low=0, high=9, when=({"question": ("heesch",)}, {"level": (3,)})),
    ),
    build=lambda values: (values, {}),
    command=lambda values: ([], {}),
)


def test_a_field_applies_under_any_of_its_conditions():
    tile = FORM.values({"seed": 1})
    assert [f.name for f in FORM.fields if f.applies(tile)] == ["question", "size", "either"]  # level is 3 by default
    heesch = FORM.values({"seed": 1, "question": "heesch", "level": 5})
    assert [f.name for f in FORM.fields if f.applies(heesch)] == ["question", "level", "either"]


def test_a_field_that_does_not_apply_takes_its_default():
    values = FORM.values({"seed": 1, "question": "tile", "level": 5, "size": "8x2"})
    assert values["level"] == 3 and values["size"] == "8x2"
    values = FORM.values({"seed": 1, "question": "heesch", "level": 5, "size": "8x2", "either": 7})
    assert values["size"] == "4x4" and values["level"] == 5 and values["either"] == 7


def test_a_value_is_still_checked_where_it_does_not_apply():
    from tilesolve.errors import InvalidProblem

    with pytest.raises(InvalidProblem, match="level"):
        FORM.values({"seed": 1, "level": 99})


def test_the_page_reads_when_as_json():
    assert FORM.fields[3].public()["when"] == [{"question": ["heesch"]}, {"level": [3]}]
    assert FORM.fields[0].public()["when"] == []


@pytest.mark.parametrize("fam", [f for f in family.families() if f.form is not None], ids=lambda f: f.name)
def test_every_condition_names_a_field_and_values_it_can_take(fam):
    fields = {f.name: f for f in fam.form.fields}
    order = list(fields)
    defaults = fam.form.values({"seed": 1})
    for f in fam.form.fields:
        for cond in f.when:
            for name, vals in cond.items():
                other = fields[name]
                # a field named earlier: its own value is settled (a default where it does not apply) first
                assert other.kind in ("choice", "int", "bool") and order.index(name) < order.index(f.name), (f.name, name)
                if other.kind == "choice":
                    assert set(vals) <= set(other.choices), (f.name, name)
                elif other.kind == "int":
                    assert all(other.low <= v <= other.high for v in vals), (f.name, name)
    assert set(defaults) == set(fields) | {"seed"}

"""Ranges that leave a chain family empty are named with what would work: the ranges widened just enough to keep
the closest traced dyad. The suggestion is checked by taking it: the family is no longer empty."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

from transplanter.errors import InfeasibleError
from transplanter.fivebar.problem import parse_problem
from transplanter.fivebar.region import chain_families
from transplanter.fivebar.synthesis import synthesize
from transplanter.toml_fields import read_toml

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "vegetable_planting.toml"


@pytest.mark.parametrize("key, bounds", [("x_e", [100.0, 200.0]), ("x_e", [-400.0, -300.0]), ("ep", [300.0, 400.0])])
def test_the_suggested_ranges_keep_a_dyad(key, bounds):
    data = read_toml(EXAMPLE)
    data["ranges"][key] = bounds
    with pytest.raises(InfeasibleError, match="no 2R chain B-E survives") as refused:
        synthesize(parse_problem(data, "f.toml"))
    advice = str(refused.value).split("what would work")[1]
    suggested = re.findall(r"ranges\.(\w+) = \[([-\d.e]+), ([-\d.e]+)\]", advice)
    assert suggested, str(refused.value)
    for name, low, high in suggested:
        data["ranges"][name] = [float(low), float(high)]
    receiving, _ = chain_families(parse_problem(data, "f.toml"))
    assert receiving.kept.sum() >= 1

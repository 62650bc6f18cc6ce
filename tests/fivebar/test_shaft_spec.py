"""The [shafts] table: given diameters kept, bad ones refused with the field, the value and what is expected."""
import tomllib
from pathlib import Path

import pytest

from transplanter.errors import ProblemError
from transplanter.fivebar.problem import parse_problem

EXAMPLE = Path(__file__).resolve().parents[2] / "examples/vegetable_planting.toml"


def _problem(shafts: dict):
    data = tomllib.loads(EXAMPLE.read_text())
    return parse_problem({**data, "shafts": shafts}, "test.toml")


def test_given_diameters_are_kept_and_the_rest_left_to_the_rules():
    assert _problem({"sun_mm": 20.0, "hinge_mm": 6.0}).shafts.diameters_mm == {"sun": 20.0, "hinge": 6.0}
    assert parse_problem(tomllib.loads(EXAMPLE.read_text())).shafts.diameters_mm == {}


@pytest.mark.parametrize(("shafts", "words"), [
    ({"sun_mm": 6.0}, ["test.toml", "shafts.sun_mm = 6.0", "over 6 and up to 130 mm", "DIN 6885-1"]),
    ({"planet_mm": 131.0}, ["shafts.planet_mm = 131.0", "over 6 and up to 130 mm"]),
    ({"hinge_mm": 0.0}, ["shafts.hinge_mm = 0.0", "over 0 and up to 130 mm"]),
    ({"intermediate_mm": "20"}, ["shafts.intermediate_mm", "20"]),
    ({"shaft_mm": 20.0}, ["shafts", "shaft_mm"]),
])
def test_bad_shafts_name_the_field_and_what_is_expected(shafts, words):
    with pytest.raises(ProblemError) as error:
        _problem(shafts)
    message = str(error.value)
    assert "\n" not in message
    for word in words:
        assert word in message

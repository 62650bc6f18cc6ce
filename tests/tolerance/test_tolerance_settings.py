"""The ``[tolerances]`` table: defaults from ISO 2768-m, and each bad entry refused naming its field."""
import math

import pytest

from tests.tolerance.linear_model import linear_model
from transplanter.errors import ProblemError
from transplanter.tolerance import analyse, parse_tolerances
from transplanter.tolerance.iso2768 import angular_limit_deg, linear_limit_mm

NAMES = ("rod_length_AF", "phase_sun")


@pytest.mark.parametrize("size, limit", [(2.0, 0.1), (30.0, 0.2), (30.01, 0.3), (249.3, 0.5), (1500.0, 1.2)])
def test_iso_2768_m_linear_limits(size, limit):
    assert linear_limit_mm(size) == limit


@pytest.mark.parametrize("leg, limit", [(8.0, 1.0), (47.97, 0.5), (84.3, 1 / 3), (300.0, 1 / 6), (500.0, 1 / 12)])
def test_iso_2768_m_angular_limits(leg, limit):
    assert angular_limit_deg(leg) == limit


def test_a_size_without_a_general_tolerance_is_refused():
    with pytest.raises(ProblemError, match="ISO 2768-m has no general tolerance"):
        linear_limit_mm(0.1)


def test_table_sets_tolerances_and_settings():
    settings = parse_tolerances({"rod_length_AF": 0.05, "distribution": "normal", "samples": 500, "seed": 3,
                                 "pose_position_mm": 2.0}, NAMES, "f.toml")
    assert settings.tolerances == {"rod_length_AF": 0.05}
    assert (settings.distribution, settings.samples, settings.seed) == ("normal", 500, 3)
    assert settings.pose_position_mm == 2.0


@pytest.mark.parametrize("table, fragment", [
    ({"rod_length_AF": -0.1}, "tolerances.rod_length_AF = -0.1: expected a finite tolerance >= 0"),
    ({"rod_length_AF": math.inf}, "tolerances.rod_length_AF = inf"),
    ({"rod_length_AF": "0.1"}, "tolerances.rod_length_AF = '0.1'"),
    ({"rod_length": 0.1}, "tolerances.rod_length = 0.1: expected a dimension name (rod_length_AF, phase_sun)"),
    ({"pose_position_mm": 0.0}, "tolerances.pose_position_mm = 0.0: expected a finite accuracy > 0"),
    ({"pose_angle_deg": -1.0}, "tolerances.pose_angle_deg = -1.0"),
    ({"distribution": "triangular"}, "tolerances.distribution = 'triangular'"),
    ({"samples": 10}, "tolerances.samples = 10"),
    ({"samples": 50_001}, "tolerances.samples = 50001: expected a whole number of Monte Carlo samples from 100 to "
                          "50000"),
])
def test_bad_entry_names_its_field(table, fragment):
    with pytest.raises(ProblemError) as error:
        parse_tolerances(table, NAMES, "f.toml")
    assert str(error.value).startswith("f.toml: ") and fragment in str(error.value)


def test_api_refuses_unknown_names_and_negative_tolerances():
    import numpy as np

    model = linear_model(np.eye(3), [0.1, 0.1, 0.1])
    with pytest.raises(ProblemError, match="tolerances.d9: unknown dimension; expected one of d0, d1, d2"):
        analyse(model, {"d9": 0.1})
    with pytest.raises(ProblemError, match="tolerances.d0 = -1.0"):
        analyse(model, {"d0": -1.0})

"""``[gears] max_pressure_angle_deg``: read with the other gear fields, refused in one line outside (nominal, 90),
and what it does to the main job's design on the fixed key poses."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from transplanter.errors import ProblemError
from transplanter.fivebar import synthesize
from transplanter.fivebar.alternatives import transmission_angles
from transplanter.fivebar.problem import parse_problem
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[2]
FIXED = ROOT / "examples/vegetable_planting.toml"


def _with_gears(**gears):
    data = {"key_poses": [{"x": float(t), "y": 0.0, "angle_deg": 0.0, "carrier_turn_deg": t} for t in (0, 18, 50, 90)],
            "return_points": [{"x": 1.0, "y": 1.0}], "gears": gears}
    return parse_problem(data, "p.toml").gearing


def test_the_limit_defaults_to_45_deg_and_is_read_in_degrees():
    assert _with_gears().max_pressure_angle == np.radians(45.0)
    assert _with_gears(pressure_angle_deg=25, max_pressure_angle_deg=38.5).max_pressure_angle == np.radians(38.5)


@pytest.mark.parametrize("gears,message", [
    ({"max_pressure_angle_deg": 20.0}, r"p.toml: gears.max_pressure_angle_deg = 20.0: expected an angle above "
                                       r"gears.pressure_angle_deg \(20\) and below 90 deg"),
    ({"pressure_angle_deg": 25, "max_pressure_angle_deg": 24}, r"gears.max_pressure_angle_deg = 24.0: expected an "
                                                               r"angle above gears.pressure_angle_deg \(25\)"),
    ({"max_pressure_angle_deg": 90}, r"gears.max_pressure_angle_deg = 90.0: expected .* below 90 deg"),
    ({"max_pressure_angle_deg": -45}, r"gears.max_pressure_angle_deg = -45.0: expected an angle above"),
    ({"max_pressure_angle_deg": "steep"}, r"gears.max_pressure_angle_deg = 'steep': expected a finite number"),
])
def test_a_limit_outside_the_nominal_angle_and_a_right_angle_is_refused_in_one_line(gears, message):
    with pytest.raises(ProblemError, match=message) as error:
        _with_gears(**gears)
    assert "\n" not in str(error.value)


def test_the_command_refuses_it_before_any_work_with_exit_2(tmp_path):
    text = (ROOT / "examples/vegetable_planting.toml").read_text()
    assert text.count("\n[gears]\n") == 1 and "max_pressure_angle_deg" not in text
    path = tmp_path / "problem.toml"
    path.write_text(text.replace("\n[gears]\n", "\n[gears]\nmax_pressure_angle_deg = 95.0\n"))
    out = tmp_path / "out"
    run = subprocess.run([sys.executable, "-m", "transplanter", "fivebar", str(path), "--out", str(out)],
                         capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert run.returncode == 2
    assert run.stderr.splitlines() == [f"transplanter: error: {path}: gears.max_pressure_angle_deg = 95.0: expected "
                                       "an angle above gears.pressure_angle_deg (20) and below 90 deg (the mesh's push "
                                       "along the motion falls as its cosine)"]
    assert not out.exists()


def _smallest_angle_at_e_deg(design) -> float:
    turns = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    at_e, _ = transmission_angles(design.mech, design.mech.forward(turns, design.relative_angle.evaluate(turns)))
    return float(np.degrees(at_e.min()))


def test_on_the_fixed_poses_the_pressure_limit_is_what_holds_the_transmission_angle_below_the_former_design(
        example_result):
    """The former design, which maximised the angle EBF, had 26.78 deg at E but a gear pressure angle of 47.35 deg,
    above the default 45 deg. With that limit the smallest angle at E is lower, and the report names the limit
    among the bounds the design sits on."""
    angle = _smallest_angle_at_e_deg(example_result.design)
    names = [bound.name for bound in example_result.chosen.active_bounds]
    assert angle >= 26.78 or "gears.max_pressure_angle_deg" in names
    assert np.degrees(example_result.pressure.largest.max()) <= 45.0 * (1 + 1e-3)


def test_with_the_pressure_limit_the_former_design_met_the_transmission_angle_is_at_least_its(tmp_path):
    """With gears.max_pressure_angle_deg = 48 the former design (47.35 deg) is a feasible point of the NLP, so the
    design that maximises the angle at E has at least its 26.78 deg (measured on the hinges). Only the design is
    read, so the tolerance analysis is not run."""
    data = read_toml(FIXED)
    data["gears"]["max_pressure_angle_deg"] = 48.0
    result = synthesize(parse_problem(data, "fixed.toml"), tolerance=False)
    assert _smallest_angle_at_e_deg(result.design) >= 26.78

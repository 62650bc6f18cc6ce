"""``[gears] max_pressure_angle_deg``: read with the other gear fields, refused in one line outside (nominal, 90)."""
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from transplanter.errors import ProblemError
from transplanter.fivebar.problem import parse_problem

ROOT = Path(__file__).resolve().parents[2]


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

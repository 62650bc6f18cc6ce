"""The cam command: JSON fields, drawings CAD can read, a failing cam, bad input (one line, exit 2)."""
import json
import math
from pathlib import Path

import ezdxf
import numpy as np
import pytest

from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/cam_seedling_support.toml"


@pytest.fixture
def run(capsys, monkeypatch):
    """``transplanter cam ARGS`` in this process (from the repository root): (exit code, stdout, stderr)."""
    monkeypatch.chdir(ROOT)

    def command(*args):
        code = main(["cam", *map(str, args)])
        out = capsys.readouterr()
        return code, out.out, out.err
    return command


def _strict_json(text):
    def refuse(name):
        raise ValueError(f"{name} in JSON")
    return json.loads(text, parse_constant=refuse)


def test_json_fields_and_drawings(tmp_path, run):
    code, stdout, stderr = run(EXAMPLE, "--json", "--no-step", "--out", tmp_path / "out")
    assert code == 0, stderr
    report = _strict_json(stdout)
    assert set(report["max_pressure_angle_deg"]) >= {"rise", "return", "at_deg"}
    assert set(report["min_curvature_radius_mm"]) >= {"pitch", "profile"}
    assert report["undercut"] is False and report["base_radius_mm"] == 30.0 and report["laws"] == ["harmonic"]
    assert len(report["acceleration_jumps"]) == 4 and report["laws_with_acceleration_jumps"] == ["harmonic"]
    assert report["files"]["drawing"] == ["cam.dxf", "cam.svg"] and report["files"]["table"] == ["cam_profile.csv"]
    assert report["files"]["figure"] == ["cam_motion.png", "cam_pressure_angle.png", "cam_profile.png"]
    out = tmp_path / "out"
    assert _strict_json((out / "report.json").read_text()) == report
    document = ezdxf.readfile(out / "cam.dxf")
    assert document.units == ezdxf.units.MM
    space = document.modelspace()
    assert {entity.dxf.layer for entity in space} == {"OUTLINE", "PITCH", "CENTERLINES", "BORE", "DIMENSIONS",
                                                       "TEXT"}
    assert [circle.dxf.radius for circle in space.query('CIRCLE[layer=="CENTERLINES"]')] == [30.0]  # base circle
    table = np.loadtxt(out / "cam_profile.csv", delimiter=",", skiprows=1)
    header = (out / "cam_profile.csv").read_text().splitlines()[0].split(",")
    profile = table[:, [header.index("profile_x_mm"), header.index("profile_y_mm")]]
    assert table.shape[0] == 3600
    assert np.linalg.norm(profile, axis=1).min() == pytest.approx(30.0, rel=1e-9)     # the base circle
    assert table[:, header.index("displacement_deg")].max() == pytest.approx(36.0, rel=1e-12)


def test_a_cam_over_the_limit_fails_with_exit_1(tmp_path, run):
    text = EXAMPLE.read_text() + "\n[limits]\npressure_angle_deg = 40.0\n"
    (tmp_path / "tight.toml").write_text(text)
    code, stdout, stderr = run(tmp_path / "tight.toml", "--json")
    assert code == 1
    assert "pressure angle on return 43.860 deg" in stderr
    assert _strict_json(stdout)["status"] == "FAILED"


TRANSLATING = """
[cam]
base_radius = 30.0
[follower]
kind = "translating"
roller_radius = 6.0
[[segments]]
kind = "rise"
angle_deg = 120.0
law = "cycloidal"
lift = 20.0
[[segments]]
kind = "dwell"
angle_deg = 60.0
[[segments]]
kind = "return"
angle_deg = 120.0
law = "cycloidal"
lift = 20.0
[[segments]]
kind = "dwell"
angle_deg = 60.0
"""

CASES = {
    "angles not a turn": (TRANSLATING.replace("angle_deg = 60.0", "angle_deg = 50.0", 1),
                          ["segments.angle_deg", "350", "adding up to 360", "+10"]),
    "negative lift": (TRANSLATING.replace("lift = 20.0", "lift = -5.0", 1), ["segments[0].lift", "-5.0", "positive"]),
    "zero lift": (TRANSLATING.replace("lift = 20.0", "lift = 0.0", 1), ["segments[0].lift", "0.0", "positive"]),
    "return below base": ("lift = 25.0".join(TRANSLATING.rsplit("lift = 20.0", 1)),
                          ["segments[2].lift", "25.0", "at most 20"]),
    "roller larger than base": (TRANSLATING.replace("roller_radius = 6.0", "roller_radius = 35.0"),
                                ["follower.roller_radius", "35.0", "less than the base radius 30"]),
    "unknown law": (TRANSLATING.replace('law = "cycloidal"', 'law = "parabolic"', 1),
                    ["segments[0].law", "parabolic", "harmonic"]),
    "swing on a translating follower": (TRANSLATING.replace("lift = 20.0", "swing_deg = 20.0", 1),
                                        ["segments[0].swing_deg", "lift for a translating"]),
    "offset beyond the pitch circle": (TRANSLATING.replace('kind = "translating"',
                                                           'kind = "translating"\noffset = 40.0'),
                                       ["follower.offset", "40.0", "less than base radius + roller radius = 36"]),
    "arm cannot reach": (EXAMPLE.read_text().replace("arm_length = 58.0", "arm_length = 20.0"),
                         ["follower.arm_length", "20.0", "from 34 to 106 mm"]),
    "pivot at the cam centre": (EXAMPLE.read_text().replace("pivot = [70.0, 0.0]", "pivot = [0.0, 0.0]"),
                                ["follower.pivot", "[0.0, 0.0]", "a pivot outside the base pitch circle"]),
    "no rise": (TRANSLATING.replace('kind = "rise"', 'kind = "dwell"', 1)
                .replace('law = "cycloidal"\nlift = 20.0\n', "", 1),
                ["segments[2].lift", "20.0", "at most 0"]),
    "limit of 90": (TRANSLATING + "[limits]\npressure_angle_deg = 95.0\n",
                    ["limits.pressure_angle_deg", "95.0", "below 90"]),
    "swing past the farthest point": (EXAMPLE.read_text().replace("swing_deg = 36.0", "swing_deg = 150.0"),
                                      ["segments.swing_deg", "largest swing of 150", "less than 149.1", "128 mm"]),
    "negative profile margin": (TRANSLATING + "[limits]\nprofile_radius_mm = -1.0\n",
                                ["limits.profile_radius_mm", "-1.0", "a radius of 0"]),
    "bore beyond the base circle": (TRANSLATING.replace("base_radius = 30.0",
                                                        "base_radius = 30.0\nbore_radius = 100.0"),
                                    ["cam.bore_radius", "100.0", "less than cam.base_radius = 30 mm"]),
    "pressure limit on a flat face": ((ROOT / "examples/cam_flat_faced.toml").read_text()
                                      .replace("[limits]\n", "[limits]\npressure_angle_deg = 20.0\n"),
                                      ["limits.pressure_angle_deg", "20.0", "none for a flat-faced follower"]),
    "base radius in design mode": (TRANSLATING + "[design]\nmax_base_radius = 100.0\n",
                                   ["cam.base_radius", "30.0", "no base radius with [design]"]),
    "no base circle meets the limit": (TRANSLATING.replace("base_radius = 30.0", "")
                                       + "[limits]\npressure_angle_deg = 5.0\n[design]\nmax_base_radius = 60.0\n",
                                       ["limits.pressure_angle_deg = 5", "no base circle up to 60",
                                        "raise design.max_base_radius"]),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_cam_input(tmp_path, run, name):
    text, parts = CASES[name]
    path = tmp_path / "bad.toml"
    path.write_text(text)
    code, stdout, stderr = run(path)
    assert code == 2, stderr
    assert stdout == "" and len(stderr.strip().splitlines()) == 1 and "Traceback" not in stderr, stderr
    for part in parts:
        assert part in stderr, (part, stderr)


def test_design_mode_from_the_command_line(run):
    code, stdout, stderr = run(ROOT / "examples/cam_translating_design.toml", "--json")
    assert code == 0, stderr
    report = _strict_json(stdout)
    assert report["designed_base_radius"] and math.isclose(max(report["max_pressure_angle_deg"]["rise"],
                                                                 report["max_pressure_angle_deg"]["return"]),
                                                             30.0, rel_tol=1e-5)


def test_designing_the_base_circle_of_a_cam_whose_base_radius_is_given_names_the_field():
    """smallest_base_radius called on a problem with a base radius (no max_base_radius): a ProblemError."""
    from transplanter import cam
    from transplanter.cam.design import smallest_base_radius
    from transplanter.errors import ProblemError

    with pytest.raises(ProblemError, match=r"cam_seedling_support.toml: max_base_radius = None: expected the "
                                           r"largest base radius to try \(mm\)"):
        smallest_base_radius(cam.load_problem(EXAMPLE))


def test_dict_with_numpy_values_gives_the_report_of_the_file():
    """As for every job (tests/api/test_python_api.py): a script's dict of numpy values reads as the file does."""
    from tests.api.test_python_api import from_dict, without_timings
    from transplanter import cam

    for name in ("cam_seedling_support.toml", "cam_translating_design.toml", "cam_flat_faced.toml"):
        from_file = cam.synthesize(cam.load_problem(ROOT / "examples" / name)).to_json()
        from_numpy = cam.synthesize(from_dict(cam, name)).to_json()
        assert without_timings(from_numpy) == without_timings(from_file)
        json.dumps(from_file, allow_nan=False)


def test_figures_are_labelled_with_legends_off_the_data():
    from tests.api.test_python_api import check_figures
    from transplanter import cam

    result = cam.synthesize(cam.load_problem(EXAMPLE))
    check_figures(cam.draw_figures(result), {"cam_motion", "cam_pressure_angle", "cam_profile"})


def test_naming_the_api_and_computing_import_no_matplotlib():
    import subprocess
    import sys

    code = ("import sys\nfrom transplanter import cam\n"
            "cam.synthesize(cam.load_problem('examples/cam_seedling_support.toml'))\n"
            "from transplanter.cam.table5 import evaluate_table5\n"
            "assert 'matplotlib' not in sys.modules, 'imported too early'\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr


def test_design_mode_fails_a_bore_the_smallest_cam_cannot_hold(tmp_path, run):
    """Design mode sizes the cam by its checks; a given bore wider than the designed profile's nearest approach to
    the centre (the base circle, for a roller follower) fails the result (exit 1) naming cam.bore_radius."""
    path = tmp_path / "bore.toml"
    example = (ROOT / "examples/cam_translating_design.toml").read_text()
    path.write_text(example.replace("[cam]", "[cam]\nbore_radius = 100.0"))
    code, stdout, stderr = run(path, "--json")
    report = _strict_json(stdout)
    assert code == 1 and report["status"] == "FAILED"
    assert report["nearest_profile_mm"]["distance"] == pytest.approx(report["base_radius_mm"], rel=1e-9)
    assert report["failures"] == [f"cam.bore_radius = 100 mm reaches the profile, which comes within "
                                  f"{report['nearest_profile_mm']['distance']:.4f} mm of the centre at cam angle "
                                  f"{report['nearest_profile_mm']['at_deg']:.2f} deg"]
    assert len(stderr.strip().splitlines()) == 1 and "cam.bore_radius" in stderr


def test_a_profile_margin_of_zero_is_the_default_written_out(run, tmp_path):
    """docs/cam.md's schema writes profile_radius_mm = 0.0, the default: the same cam as without the line."""
    path = tmp_path / "zero.toml"
    path.write_text(TRANSLATING + "[limits]\nprofile_radius_mm = 0.0\n")
    plain = tmp_path / "plain.toml"
    plain.write_text(TRANSLATING)
    (code, out, _), (code_plain, out_plain, _) = run(path, "--json"), run(plain, "--json")
    assert code == code_plain == 0
    def drop(report):
        return {k: v for k, v in report.items() if k not in ("source", "timings_s")}

    assert drop(_strict_json(out)) == drop(_strict_json(out_plain))

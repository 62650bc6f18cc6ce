"""`transplanter reverse`: report fields, figures, and one clear line with exit 2 for bad input."""
import json
from pathlib import Path

import numpy as np
import pytest

from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
RICE_FILE = ROOT / "examples" / "rice_hoe_reverse.toml"
RICE = RICE_FILE.read_text()


def _points(points) -> str:
    return "[" + ", ".join(f"[{x!r}, {y!r}]" for x, y in np.asarray(points, float).tolist()) + "]"


def _ellipse(count=12, a=200.0, b=150.0, center=(0.0, 0.0)):
    x = np.linspace(0, 2 * np.pi, count, endpoint=False)
    return np.c_[center[0] + a * np.cos(x), center[1] + b * np.sin(x)]


def _problem(points, kind="samples", arm="", train=""):
    return f'[trajectory]\nkind = "{kind}"\npoints = {_points(points)}\n[arm]\n{arm}\n[train]\n{train}\n'


def _run(tmp_path, text, *flags):
    path = tmp_path / "problem.toml"
    path.write_text(text)
    return main(["reverse", str(path), *flags])


def test_json_report_has_the_design_fields_and_the_figures(tmp_path, capsys, rice_result_from_synthesize):
    """Without the tolerance analysis (its report and figures: tests/reverse/test_tolerance_model.py). The train
    is the session's ``rice_result``, the example file's as this command synthesises it."""
    out = tmp_path / "out"
    assert main(["reverse", str(RICE_FILE), "--json", "--no-step", "--no-tolerance", "--out", str(out)]) == 0
    report = json.loads(capsys.readouterr().out)
    for field in ("monotonic", "violations", "carrier_length", "arm_length", "ratio_range", "gear_closure_errors",
                  "roundtrip_max_error_mm", "branch_segments", "branch_switches_u", "gears"):
        assert field in report
    assert report["monotonic"] is True and report["violations"] == []
    assert report["roundtrip_max_error_mm"] < 1e-6
    assert 0 < report["ratio_range"][0] < 1 < report["ratio_range"][1]
    assert {p.name for p in (tmp_path / "out").iterdir()} >= {"report.md", "report.json", "path.png", "motion.png",
                                                              "gears.png"}


def test_non_monotonic_path_reports_where_and_exits_2(tmp_path, capsys):
    """An ellipse round the pivot with the arm never straight nor folded: the gears stop where the
    distance from the pivot is stationary; the report names the intervals, the CLI exits 2."""
    code = _run(tmp_path, _problem(_ellipse(), arm="carrier_length = 100.0\narm_length = 140.0"), "--json")
    out, err = capsys.readouterr()
    report = json.loads(out)
    assert code == 2
    assert report["monotonic"] is False
    gears = [v for v in report["violations"] if v["condition"] == "gears"]
    assert gears and all(0 <= v["u"][0] <= 1 and 0 <= v["u"][1] <= 1 for v in gears)
    assert "monotonicity criterion" in err and "gears would reverse" in err
    assert report["fix_hints"]


BAD = {
    "open curve": (_problem(_ellipse(12)[:7]), ["trajectory.points", "closed curve", "looks open"]),
    "collinear": (_problem([[0, 0], [10, 0], [20, 0], [30, 0], [40, 0]]), ["trajectory.points", "one line"]),
    "repeated point": (_problem(np.r_[_ellipse(8)[:3], _ellipse(8)[2:]]), ["trajectory.points[3]", "distinct"]),
    "cusp": (_problem([[0, 0], [100, 0], [150, 50], [100, 0], [100, 100], [0, 100]], kind="control_points"),
             ["trajectory.points", "the curve stops", "u = 0.3333", "folds straight back"]),
    "too few": (_problem(_ellipse(3)), ["trajectory.points", "at least 4"]),
    "kind": (_problem(_ellipse(), kind="spline"), ["trajectory.kind", "spline", "control_points"]),
    "one length": (_problem(_ellipse(), arm="carrier_length = 50.0"), ["arm.carrier_length", "neither"]),
    "negative length": (_problem(_ellipse(), arm="carrier_length = -5.0\narm_length = 200.0"),
                        ["arm.carrier_length", "-5.0", "positive"]),
    "direction": (_problem(_ellipse(), arm='direction = "cw"'), ["arm.direction", "cw", "clockwise"]),
    "unreachable": (_problem(_ellipse(), arm="carrier_length = 60.0\narm_length = 100.0"),
                    ["beyond the reach s + l = 160.0000", "by up to", "u = ", "lengths with s + l >= ",
                     "reach every point"]),
    "hole": (_problem(_ellipse(a=40, b=30), arm="carrier_length = 20.0\narm_length = 80.0"),
             ["inside the hole |s - l| = 60.0000", "by up to"]),
    "split for topology": (_problem(_ellipse(), train='topology = "sun-idler-planet"\nsplit = "sqrt"'),
                           ["train.split", "sqrt", "identical_sun_planet"]),
    "peak to valley": (_problem(_ellipse(), train='split = "peak_to_valley"\npeak_to_valley = 1.5'),
                       ["train.peak_to_valley", "1.5", "(0, 1)"]),
    "peak to valley with another split": (_problem(_ellipse(), train='split = "sqrt"\npeak_to_valley = 0.6'),
                                          ["train.peak_to_valley", "0.6", 'none with split = "sqrt"']),
    "unknown key": (_problem(_ellipse(), train="gears = 4"), ["train.gears", "no such field"]),
    "no trajectory": ("[arm]\n", ["trajectory", "kind and points"]),
}


@pytest.mark.parametrize("name", BAD)
def test_bad_input_is_one_clear_line(tmp_path, capsys, name):
    text, expected = BAD[name]
    assert _run(tmp_path, text) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("transplanter: error:")
    for fragment in expected:
        assert fragment in err, (fragment, err)


def test_center_distances_that_cannot_place_the_planet(tmp_path, capsys):
    text = RICE.replace('topology = "sun-intermediate-planet"', 'topology = "pick-up"\ncenter_distances = [20.0, 30.0]')
    assert _run(tmp_path, text) == 2
    assert "train.center_distances" in capsys.readouterr().err
    text = RICE.replace('split = "sqrt"', 'split = "sqrt"\ncenter_distances = [40.0, 40.0]')
    assert _run(tmp_path, text) == 2
    assert "can place the planet 92.3 mm from the pivot" in capsys.readouterr().err    # on a bent carrier
    text = RICE.replace('topology = "sun-intermediate-planet"', 'topology = "sun-idler-planet"').replace(
        'split = "sqrt"', 'split = "identical_sun_planet"\ncenter_distances = [40.0, 52.3]')
    assert _run(tmp_path, text) == 2
    assert "expected two equal distances for sun-idler-planet" in capsys.readouterr().err
    text = RICE.replace('topology = "sun-intermediate-planet"', 'topology = "pick-up"\ncenter_distances = [1e-9, 92.3]')
    assert _run(tmp_path, text) == 2                            # a stage of gears a billionth of the train
    assert "expected each at least 0.001 of the carrier length" in capsys.readouterr().err


def test_idler_train_report_says_how_far_it_misses(rice_idler_command):
    """The command on the rice hoe turned into the paper's idler train (``rice_idler_command``: run once for this
    and the paper's test in test_reverse_design.py, which reads its train)."""
    assert rice_idler_command.code == 1                                # a failed check, the report says which
    report = json.loads(rice_idler_command.out)
    assert report["status"] == "FAILED" and "misses the path by up to" in report["failures"][0]
    assert len(rice_idler_command.err.strip().splitlines()) == 1
    assert report["idler_iteration"]["settled"] is False
    assert report["roundtrip_max_error_mm"] > 1.0
    assert len(report["gear_closure_errors"]) == 2 and max(map(abs, report["gear_closure_errors"])) < 1e-9
    sun, idler, planet = report["gears"]
    assert planet["radius_range_mm"] == pytest.approx(sun["radius_range_mm"], abs=1e-6)   # conjugates of one idler

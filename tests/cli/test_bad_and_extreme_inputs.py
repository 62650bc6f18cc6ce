"""Bad, extreme and transformed inputs. Each kind of failure that feeding the commands such inputs found is
pinned here: one clear line and exit 2 for bad input, checked before the work; exit 1 and FAILED- files
for a result that fails a check; never a traceback, a numpy warning or a report that is not JSON."""
import json
import re
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from transplanter import burmester, cam, fivebar, gears, parallelogram, reverse
from transplanter.cli import main
from transplanter.errors import ProblemError
from transplanter.output_folder import report_json

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
pytestmark = pytest.mark.filterwarnings("error")      # a numpy warning is a failure, never output


def _variant(tmp_path, example: str, *replacements) -> str:
    """The example with each (pattern, text) replaced once, written beside the test."""
    text = (EXAMPLES / example).read_text()
    for pattern, new in replacements:
        assert re.search(pattern, text, flags=re.M), pattern
        text = re.sub(pattern, new.replace("\\", "\\\\"), text, count=1, flags=re.M)   # new taken literally
    path = tmp_path / example
    path.write_text(text)
    return str(path)


RICE_POINT_2 = r"\[22.307237065475743, -85.18514875915126\]"

# name: (command, example, replacements, extra arguments, fragments of the one error line)
BAD = {
    "file is a folder": ("burmester", None, (), (), ["a folder; expected a TOML problem file"]),
    "out unwritable": ("burmester", "burmester_4poses.toml", (), ("--out", "/proc/x"),
                       ["--out = /proc/x", "cannot write"]),
    "plot unknown format": ("burmester", "burmester_4poses.toml", (), ("--plot", "{tmp}/x.xyz"), ["--plot", ".png"]),
    "plot is a folder": ("burmester", "burmester_4poses.toml", (), ("--plot", "{tmp}/figure.png"),
                         ["--plot", "a folder is there"]),
    "coordinate overflows": ("burmester", "burmester_4poses.toml", (("x = -23.1", "x = 1e308"),), (),
                             ["poses[0].x = 1e+308", "within ±1e+09"]),
    "angle far beyond a turn": ("burmester", "burmester_4poses.toml", (("angle_deg = 113.8", "angle_deg = 1e300"),), (),
                                ["poses[0].angle_deg = 1e+300", "within ±1e+06"]),
    "reverse point overflows": ("reverse", "rice_hoe_reverse.toml", ((RICE_POINT_2, "[1e308, 1e308]"),), (),
                                ["trajectory.points[2] = [1e+308, 1e+308]", "within ±1e+09"]),
    "design is a folder": ("fivebar", "vegetable_planting.toml", (), ("--design", "{tmp}"), ["a folder; expected"]),
    "key poses coincide": ("fivebar", "vegetable_planting.toml", (("x = -51.1\ny = -314.6\nangle_deg = 100.0",
                                                                  "x = -23.1\ny = -309.7\nangle_deg = 113.8"),), (),
                           ["key_poses[1] = ", "different from key_poses[0]"]),
    "return point out of reach": ("fivebar", "vegetable_planting.toml", (("x = -125.0", "x = 300000.0"),), (),
                                  ["return_points[0] = [300000.0, -287.0]", "P stays within"]),
    "return point on a key pose": ("fivebar", "vegetable_planting.toml", (("x = -125.0\ny = -287.0",
                                                                          "x = -23.1\ny = -309.7"),), (),
                                   ["return_points[0] = [-23.1, -309.7]", "on key_poses[0]"]),
    "module underflows": ("gear", "gear_ellipse.toml", (("module = 2.0", "module = 1e-300"),), (),
                          ["pair.module = 1e-300", "from 1e-09 to 1e+09 mm"]),
    "design length overflows": ("fivebar", "vegetable_planting.toml", (), ("--design", "{design}"),
                                ["design.carrier_length_OA = 1e+308"]),
    "ratio formula not finite": ("gear", "gear_ratio_formula.toml",
                                 (('expression = ".*"', 'expression = "1e308*(2+cos(phi))"'),), (),
                                 ["driver.expression = '1e308*(2+cos(phi))' reaches inf", "finite ratio"]),
    "ratio formula too large": ("gear", "gear_ratio_formula.toml",
                                (('expression = ".*"', 'expression = "1e300*(2+cos(phi))"'),), (),
                                ["driver.expression", "from 0.001 to 1000"]),
    "ratio formula negative": ("gear", "gear_ratio_formula.toml",
                               (('expression = ".*"', 'expression = "cos(phi)"'),), (),
                               ["driver.expression = 'cos(phi)' reaches -1 at phi = 180.00 deg", "reverses"]),
    "ratio formula too long": ("gear", "gear_ratio_formula.toml", (('expression = ".*"', 'expression = "' + "(" * 3000
                                                                   + "phi" + ")" * 3000 + '"'),),
                               (), ["driver.expression = '(((", "(6005 characters)", "at most 1000"]),
    "ratio samples far beyond a turn": ("gear", "gear_ratio.toml",
                                        (("phi_deg = \\[[^\\]]*\\]", "phi_deg = [1e308, 90, 180, 270]"),), (),
                                        ["driver.phi_deg", "within ±1e+06"]),
    "limacon amplitude reaches the base": ("gear", "gear_limacon.toml", (("amplitude = 8.0", "amplitude = 50.0"),), (),
                                           ["driver.amplitude = 50.0", "below driver.base = 50"]),
    "teeth beyond what is cut": ("gear", "gear_ellipse.toml", (("teeth = 30", "teeth = 20001"),), (),
                                 ["pair.teeth = 20001", "from 3 to 20000"]),
    "teeth beyond what a shaper cuts": ("gear", "gear_concave_shaper.toml", (("teeth = 60", "teeth = 1001"),), (),
                                        ["pair.teeth = 1001", "at most 1000 with cutter = \"shaper\""]),
    "composite teeth beyond what is carved": ("gear", "gear_cusp_composite.toml", (("teeth = 30", "teeth = 201"),), (),
                                              ["pair.teeth = 201", "at most 200 with family = \"composite\""]),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_gives_one_line_and_exit_2_before_the_work(tmp_path, capsys, monkeypatch, name):
    command, example, replacements, extra, fragments = BAD[name]
    (tmp_path / "figure.png").mkdir()
    design = _variant(tmp_path, "vegetable_planting_table4.toml",
                      (r"carrier_length_OA = .*", "carrier_length_OA = 1e308"))
    path = _variant(tmp_path, example, *replacements) if example else str(tmp_path)
    extra = [arg.format(tmp=tmp_path, design=design) for arg in extra]
    for job in (burmester, gears, fivebar, reverse):         # checked before the work: no synthesis starts
        monkeypatch.setattr(job, "synthesize", lambda *a, **k: pytest.fail("the work started"))
    assert main([command, path, "--quiet", *extra]) == 2
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("transplanter: error: "), captured.err
    for fragment in fragments:
        assert fragment in lines[0], (fragment, lines[0])
    assert captured.out == ""
    assert not (tmp_path / "x.xyz").exists()


@pytest.mark.parametrize("job", [burmester, gears, fivebar, reverse])
@pytest.mark.parametrize("value", [None, 42, "", {}, "examples/burmester_4poses.toml"])
def test_the_api_names_what_it_was_given(job, value):
    with pytest.raises(ProblemError, match="path = |problem = |: poses|: driver|: key_poses|: trajectory"):
        job.parse_problem(value) if isinstance(value, dict) else job.load_problem(value if value != "examples/"
                                                                                  "burmester_4poses.toml" else 42)
    with pytest.raises(ProblemError, match=r"problem = .*expected a \w+Problem \(from transplanter\."):
        job.synthesize(value)


@pytest.mark.parametrize("job", [cam, parallelogram])
@pytest.mark.parametrize("value", [None, 42, "", {}, "examples/cam_seedling_support.toml"])
def test_cam_and_parallelogram_synthesis_name_what_they_were_given(job, value):
    with pytest.raises(ProblemError, match=r"problem = .*expected a \w+Problem \(from transplanter\."):
        job.synthesize(value)


@pytest.mark.parametrize("job, problem",
                         [(fivebar, "vegetable_planting.toml"), (parallelogram, "onion_transplanter.toml")])
def test_evaluating_a_design_names_what_it_was_given(job, problem):
    with pytest.raises(ProblemError, match=r"problem = None: expected a \w+Problem"):
        job.evaluate_design(None, None)
    with pytest.raises(ProblemError, match=r"= 'x': expected a \w+ \(from transplanter\.\w+\.load_design\(path\)\)"):
        job.evaluate_design(job.load_problem(ROOT / "examples" / problem), "x")


@pytest.mark.parametrize("poses", [[[1, 2, 3]], [[0, 0], [1, 0], [2, 0], [3, 1]], [[0, 0, 0], [1, 0, 0.2]],
                                   [[0, 0, 0], [1, 0, 0.2], [2, 1e12, 0.4]]])
def test_poses_of_the_wrong_shape_or_size_are_named(poses):
    with pytest.raises(ProblemError, match="DyadProblem.poses = "):
        burmester.DyadProblem(poses=poses)


def _poses_turning_about(centre, angles_deg, reference=(0.0, 0.0)) -> str:
    text = ""
    for angle in np.radians(angles_deg):
        c, s = np.cos(angle), np.sin(angle)
        x, y = np.subtract(reference, centre)
        text += (f"[[poses]]\nx = {float(centre[0] + c * x - s * y)!r}\ny = {float(centre[1] + s * x + c * y)!r}\n"
                 f"angle_deg = {float(np.degrees(angle))!r}\n")
    return text


@pytest.mark.parametrize("centre, reference, angles", [((0.0, 0.0), (0.0, 0.0), (0, 30, 60, 90)),
                                                       ((0.0, 0.0), (0.0, 0.0), (0, 30, 60, 90, 120)),
                                                       ((0.0, 0.0), (0.0, 0.0), (0, 30, 60, 90, 120, 150)),
                                                       ((100.0, -40.0), (3.0, 5.0), (0, 20, 45, 80))])
def test_a_pure_rotation_is_named_and_answered(tmp_path, capsys, centre, reference, angles):
    """Poses that only turn about one point: every dyad centred there fits, whatever its circle point."""
    path = tmp_path / "rotation.toml"
    path.write_text(_poses_turning_about(centre, angles, reference))
    assert main(["burmester", str(path), "--json"]) == 0
    report = json.loads(capsys.readouterr().out)
    assert "pure rotation about" in report["method"]
    assert len(report["dyads"]) == 1
    dyad = report["dyads"][0]
    np.testing.assert_allclose(dyad["center"], centre, atol=1e-9 * max(1, np.hypot(*centre)))
    assert dyad["length"] > 0 and max(abs(r) for r in dyad["residuals_mm"]) <= 1e-9 * dyad["length"]


def test_no_dyad_found_is_a_failed_result(tmp_path, capsys):
    path = _variant(tmp_path, "burmester_4poses.toml", ("radius_mm = 400.0", "radius_mm = 0.5"))
    assert main(["burmester", path, "--out", str(tmp_path / "out"), "--quiet"]) == 1
    assert "no dyad found within search.radius_mm = 0.5 mm" in capsys.readouterr().err
    assert (tmp_path / "out" / "FAILED-report.json").exists()


class _SelfCrossing:
    """A gear result whose tooth outlines cross themselves."""

    def __init__(self, result):
        self._result = result
        self.teeth = type("Teeth", (), {"self_intersections": (4, 4), "outlines": result.teeth.outlines})()

    def __getattr__(self, name):
        return getattr(self._result, name)


def test_gear_with_self_crossing_teeth_exits_1_with_failed_files(tmp_path, capsys, monkeypatch):
    real = gears.synthesize(gears.load_problem(EXAMPLES / "gear_ellipse.toml"))
    assert real.passed and real.failures == []
    crossing = _SelfCrossing(real)
    crossing_failures = gears.GearResult.failures.fget(crossing)
    assert "driver 4, driven 4 crossings" in crossing_failures[0]
    monkeypatch.setattr(gears, "synthesize", lambda problem: real)
    monkeypatch.setattr(gears.GearResult, "failures", property(lambda self: crossing_failures))
    monkeypatch.setattr(gears.GearResult, "write_files", lambda result, folder, animation=True, solids=True: [])
    monkeypatch.setattr(gears.GearResult, "figure_drawers", lambda result: {"gears": lambda: Figure(figsize=(1, 1))})
    out = tmp_path / "out"
    assert main(["gear", str(EXAMPLES / "gear_ellipse.toml"), "--out", str(out), "--quiet", "--no-step"]) == 1
    assert "tooth outlines cross themselves" in capsys.readouterr().err
    assert all(p.name.startswith("FAILED-") for p in out.iterdir())


def test_a_given_design_that_violates_a_condition_exits_1(capsys):
    code = main(["fivebar", str(EXAMPLES / "vegetable_planting.toml"), "--design",
                 str(EXAMPLES / "vegetable_planting_table4.toml"), "--json"])
    report = json.loads(capsys.readouterr().out)
    assert report["violations"] and code == 1 and report["status"] == "FAILED"
    assert report["failures"] == report["violations"]


def _small_burmester_figures(monkeypatch):
    monkeypatch.setattr(burmester.Synthesis, "figure_drawers",
                        lambda result: {"burmester": lambda: Figure(figsize=(1, 1))})


def test_interrupt_leaves_no_output_and_one_line(tmp_path, capsys, monkeypatch):
    def interrupted(problem):
        raise KeyboardInterrupt
    monkeypatch.setattr(burmester, "synthesize", interrupted)
    out = tmp_path / "out"
    assert main(["burmester", str(EXAMPLES / "burmester_4poses.toml"), "--out", str(out)]) == 130
    assert capsys.readouterr().err.strip() == f"transplanter: interrupted; {out} is left as it was"
    assert list(tmp_path.iterdir()) == []


def test_a_write_that_fails_midway_is_one_line_and_keeps_the_earlier_output(tmp_path, capsys, monkeypatch):
    _small_burmester_figures(monkeypatch)
    out = tmp_path / "out"
    assert main(["burmester", str(EXAMPLES / "burmester_4poses.toml"), "--out", str(out), "--quiet"]) == 0
    earlier = {p.name: p.read_bytes() for p in out.iterdir()}

    def disk_full(figure, path, dpi):
        raise OSError(28, "No space left on device", str(path))
    import transplanter.cli as cli
    monkeypatch.setattr(cli, "_save_figure", disk_full)
    assert main(["burmester", str(EXAMPLES / "burmester_4poses.toml"), "--out", str(out), "--quiet"]) == 2
    line = capsys.readouterr().err.strip()
    assert line.endswith(f"burmester.png: No space left on device; {out} is left as it was")
    assert {p.name: p.read_bytes() for p in out.iterdir()} == earlier
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_plot_is_written_whole(tmp_path, monkeypatch):
    _small_burmester_figures(monkeypatch)
    plot = tmp_path / "figure.svg"
    assert main(["burmester", str(EXAMPLES / "burmester_4poses.toml"), "--plot", str(plot), "--quiet"]) == 0
    assert plot.read_text().lstrip().startswith("<?xml") and [p.name for p in tmp_path.iterdir()] == ["figure.svg"]


def test_reports_are_json_without_nan_or_infinity():
    text = report_json({"a": float("nan"), "b": [1.0, float("inf"), {"c": -float("inf")}], "d": 2.5})
    assert json.loads(text) == {"a": None, "b": [1.0, None, {"c": None}], "d": 2.5}


@pytest.mark.parametrize("limits", [{"ratio": [0.9, 1.2]}, {"min_closure_margin": 0.3},
                                    {"ratio": [0.8, 1.5], "min_closure_margin": 0.2}])
def test_an_infeasible_five_bar_says_which_limit_to_move_and_that_value_admits_a_pair(limits):
    """Limits no pair of the example meets: the message gives new [conditions] values, and a problem with
    those values has a feasible pair (the hint's ground truth is the region judged again)."""
    from transplanter.errors import InfeasibleError
    from transplanter.fivebar.problem import parse_problem
    from transplanter.fivebar.region import solution_region
    from transplanter.fivebar.relaxation import relaxation
    from transplanter.toml_fields import read_toml

    data = read_toml(EXAMPLES / "vegetable_planting.toml")
    data["region"]["samples"] = 300
    data["conditions"].update(limits)
    problem = parse_problem(data, "strict.toml")
    with pytest.raises(InfeasibleError, match="fails only on limits; it passes with conditions") as caught:
        fivebar.synthesize(problem)
    assert "\n" not in str(caught.value)
    change = relaxation(problem, solution_region(problem))
    assert set(change) - {"candidate"} == {f"conditions.{key}" for key in limits} | (
        {"conditions.min_closure_margin"} if "ratio" in limits else set())
    for field, value in change.items():
        if field != "candidate":
            assert f"{field} = " in str(caught.value)
            data["conditions"][field.split(".")[1]] = value
    assert solution_region(parse_problem(data, "relaxed.toml")).feasible


def test_an_infeasible_five_bar_with_no_limit_to_move_says_what_else_to_change():
    """Ranges so tight that every pair fails on its geometry (return stroke, branch, crank): the hint
    names the ranges, the region and the key poses, with the dyads kept. The region is sampled coarsely
    (320 samples, where 280-350 all leave such pairs only; at 300 one pair fails on its closure margin alone)."""
    from transplanter.errors import InfeasibleError
    from transplanter.toml_fields import read_toml

    data = read_toml(EXAMPLES / "vegetable_planting.toml")
    data["region"]["samples"] = 320
    data["ranges"]["ep"] = [55.0, 80.0]
    problem = fivebar.parse_problem(data, "tight.toml")
    with pytest.raises(InfeasibleError, match=r"no limit changes; the ranges and region keep \d+ of \d+ B-E dyads"):
        fivebar.synthesize(problem)

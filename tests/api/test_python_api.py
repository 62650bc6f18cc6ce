"""The Python API of every job: problems from dicts holding numpy values give the same reports as
the TOML files, results carry their JSON, figures come back as Figure objects with units and the
legend off the data, and a problem class built with degrees is refused clearly."""
import functools
import json
import pickle
import subprocess
import sys
from importlib.metadata import version
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from transplanter import burmester, fivebar, gears, reverse
from transplanter.cli import main
from transplanter.errors import ProblemError
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples"
JOBS = {"burmester": burmester, "fivebar": fivebar, "gears": gears, "reverse": reverse}


def numpy_like(value):
    """What a script would build: numpy arrays for lists of numbers, numpy scalars for numbers,
    tuples of tables; strings as they are."""
    if isinstance(value, dict):
        return {key: numpy_like(item) for key, item in value.items()}
    if isinstance(value, list):
        if value and all(isinstance(item, dict) for item in value):
            return tuple(numpy_like(item) for item in value)
        return np.array(value)
    if isinstance(value, bool):
        return np.bool_(value)
    if isinstance(value, int):
        return np.int64(value)
    if isinstance(value, float):
        return np.float64(value)
    return value


def without_timings(report: dict) -> dict:
    """The report without its wall times (``timings_s`` at any depth: the tolerance analysis's, a toothed
    train's)."""
    return {key: without_timings(value) if isinstance(value, dict) else value
            for key, value in report.items() if key != "timings_s"}


@functools.cache
def file_result(job, name: str):
    """``job``'s result of the example file ``name``, synthesised once per test process (the limacon gear pair is
    read by two tests here; the rice hoe's reverse train is the session's ``rice_full_result``)."""
    return job.synthesize(job.load_problem(EXAMPLES / name))


def from_dict(job, name: str):
    """The example's problem built from its content turned into numpy values (same source name)."""
    path = EXAMPLES / name
    return job.parse_problem(numpy_like(read_toml(path)), str(path))


@pytest.mark.parametrize("job, name", [(burmester, "burmester_relative.toml"), (burmester, "burmester_3poses.toml"),
                                       (burmester, "burmester_5poses.toml"), (gears, "gear_ratio.toml"),
                                       (gears, "gear_limacon.toml"), (reverse, "rice_hoe_reverse.toml"),
                                       (reverse, "pickup_arm_reverse.toml")])
def test_dict_with_numpy_values_gives_the_report_of_the_file(job, name, request):
    # the reverse trains of the files are the session's (the README's example and the published findings read them)
    shared = {"rice_hoe_reverse.toml": "rice_full_result", "pickup_arm_reverse.toml": "pickup_full_result"}
    if name in shared:
        # a problem from the dict that pickles as the file's (every field of the same type and bits) gets the
        # session's train of the file (the synthesis is deterministic), as the five-bar's below is judged; one
        # that differs in any field or type is synthesised and its whole report compared
        request.getfixturevalue("rice_result_from_synthesize")
    of_file = request.getfixturevalue(shared[name]) if name in shared else file_result(job, name)
    report = of_file.to_json()
    from_numpy = job.synthesize(from_dict(job, name)).to_json()
    assert without_timings(from_numpy) == without_timings(report)
    json.dumps(report, allow_nan=False)


def test_fivebar_dict_with_numpy_values_gives_the_problem_of_the_file(example_result):
    """The five-bar problem from a dict of numpy values pickles to the same bytes as the file's: every field
    has the same type and the same bits, so the synthesis (deterministic, and tens of seconds: the other jobs'
    reports are compared whole above) gives the file's report; that report is plain JSON."""
    from_file = fivebar.load_problem(EXAMPLES / "vegetable_planting.toml")
    assert pickle.dumps(from_dict(fivebar, "vegetable_planting.toml")) == pickle.dumps(from_file)
    assert pickle.dumps(example_result.problem) == pickle.dumps(from_file)
    json.dumps(example_result.to_json(), allow_nan=False)


def test_evaluation_report_is_plain_json():
    problem = fivebar.load_problem(EXAMPLES / "vegetable_planting.toml")
    evaluation = fivebar.evaluate_design(problem, fivebar.load_design(EXAMPLES / "vegetable_planting_table4.toml"))
    report = evaluation.to_json()
    assert json.loads(json.dumps(report, allow_nan=False)) == report
    assert len(report["key_pose_position_errors_mm"]) == 4


def test_report_json_written_by_the_command_is_to_json(tmp_path):
    path = EXAMPLES / "burmester_4poses.toml"
    assert main(["burmester", str(path), "--out", str(tmp_path)]) == 0
    written = json.loads((tmp_path / "report.json").read_text())
    assert written.pop("files") == {"figure": ["burmester.png"], "report": ["report.json", "report.md"]}
    assert written == burmester.synthesize(burmester.load_problem(path)).to_json()


def _labelled(ax) -> bool:
    """An axes shows its quantities and units: x and y labels, on it or on an axes sharing that axis."""
    return (any(other.get_xlabel() for other in ax.get_shared_x_axes().get_siblings(ax))
            and any(other.get_ylabel() for other in ax.get_shared_y_axes().get_siblings(ax)))


def _overlaps(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def check_figures(figures: dict, stems: set[str]):
    assert set(figures) == stems
    for stem, figure in figures.items():
        assert isinstance(figure, Figure), stem
        figure.draw_without_rendering()
        shown = [ax for ax in figure.axes if ax.axison]
        assert shown and all(_labelled(ax) for ax in shown), stem
        legends = [legend for ax in figure.axes for legend in [ax.get_legend()] if legend] + figure.legends
        for legend in legends:
            box = legend.get_window_extent()
            assert not any(_overlaps(box, ax.get_window_extent()) for ax in shown), stem


def test_the_main_job_result_pickles(example_result):
    import pickle

    again = pickle.loads(pickle.dumps(example_result))
    reports = [r.to_json() for r in (example_result, again)]
    for report in reports:
        report.pop("timings_s")
    assert json.dumps(reports[0]) == json.dumps(reports[1])


def test_figures_of_each_job(example_result, rice_full_result):
    check_figures(fivebar.draw_figures(example_result),
                  {"region", "relative_angle", "gears", "trajectory", "tradeoff", "loads", "pressure_angle",
                   "tolerance_trajectory", "tolerance_band", "tolerance_contributions"})
    four_poses = burmester.load_problem(EXAMPLES / "burmester_4poses.toml")
    check_figures(burmester.draw_figures(burmester.synthesize(four_poses)), {"burmester"})
    check_figures(gears.draw_figures(file_result(gears, "gear_limacon.toml")),
                  {"gear_mesh", "gear_kinematics", "gear_curvature"})
    check_figures(reverse.draw_figures(rice_full_result),
                  {"path", "motion", "gears", "tolerance_trajectory", "tolerance_band", "tolerance_contributions"})


def test_naming_the_api_and_computing_import_no_matplotlib():
    code = ("import sys\nfrom transplanter import burmester, fivebar, gears, reverse\n"
            "for job in (burmester, fivebar, gears, reverse):\n"
            "    job.load_problem, job.parse_problem, job.synthesize\n"
            "fivebar.evaluate_design, fivebar.load_design\n"
            "assert 'matplotlib' not in sys.modules, 'imported too early'\n"
            "fivebar.draw_figures\n"
            "assert 'matplotlib' in sys.modules\n"
            "assert 'matplotlib.pyplot' not in sys.modules, 'figures use pyplot'\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr


def _five_bar_fields(angle_unit):
    problem = fivebar.load_problem(EXAMPLES / "vegetable_planting.toml")
    poses = problem.poses.copy()
    poses[:, 2] = angle_unit(poses[:, 2])
    return dict(poses=poses, carrier_turns=problem.carrier_turns, return_points=problem.return_points,
                labels=problem.labels, return_labels=problem.return_labels)


def test_fivebar_problem_built_with_degrees_is_refused_clearly():
    fields = _five_bar_fields(np.degrees)
    with pytest.raises(ProblemError, match=r"FiveBarProblem\.poses = .*113\.8.*radians.*parse_problem"):
        fivebar.FiveBarProblem(**fields)
    fields = _five_bar_fields(lambda angles: angles)
    fields["carrier_turns"] = np.array([0.0, 18.0, 50.0, 90.0])
    with pytest.raises(ProblemError, match=r"FiveBarProblem\.carrier_turns = \[0\.0, 18\.0, 50\.0, 90\.0\].*2 pi"):
        fivebar.FiveBarProblem(**fields)
    fields["carrier_turns"] = np.radians([0.0, 18.0, 50.0])
    with pytest.raises(ProblemError, match=r"FiveBarProblem\.carrier_turns.*shape \(4,\)"):
        fivebar.FiveBarProblem(**fields)
    fields = _five_bar_fields(lambda angles: angles)
    fields["return_points"] = np.array([[1.0, np.nan]])
    with pytest.raises(ProblemError, match=r"FiveBarProblem\.return_points.*finite"):
        fivebar.FiveBarProblem(**fields)


def test_other_problem_classes_built_with_degrees_are_refused():
    poses = np.array([[0.0, 0.0, 0.0], [10.0, 2.0, 20.0], [20.0, 1.0, 45.0], [30.0, -3.0, 60.0]])
    with pytest.raises(ProblemError, match=r"DyadProblem\.poses.*radians"):
        burmester.DyadProblem(poses)
    gear = gears.load_problem(EXAMPLES / "gear_limacon.toml")
    with pytest.raises(ProblemError, match=r"GearProblem\.pressure_angle = 20\.0.*radians"):
        gears.GearProblem(**{**gear.__dict__, "pressure_angle": 20.0})
    path = reverse.load_problem(EXAMPLES / "rice_hoe_reverse.toml")
    with pytest.raises(ProblemError, match=r"ReverseProblem\.points.*shape \(m, 2\)"):
        reverse.ReverseProblem(**{**path.__dict__, "points": path.points.ravel()})


@pytest.mark.parametrize("name", sorted(JOBS))
@pytest.mark.parametrize("data", [None, 42, "key_poses", [1, 2]])
def test_parse_problem_of_no_table_names_what_was_expected(name, data):
    with pytest.raises(ProblemError, match=r"<dict>: problem = .*: expected a table of fields"):
        JOBS[name].parse_problem(data)


@pytest.mark.parametrize("name", sorted(JOBS))
@pytest.mark.parametrize("path", [None, 42, {}, ""])
def test_load_problem_of_no_file_name_names_what_was_expected(name, path):
    with pytest.raises(ProblemError, match=r"path = .*: expected the name of a TOML problem file"):
        JOBS[name].load_problem(path)


def test_load_problem_of_a_folder(tmp_path):
    with pytest.raises(ProblemError, match=r"a folder; expected a TOML problem file"):
        fivebar.load_problem(tmp_path)


def test_numpy_values_are_checked_like_toml_values():
    data = numpy_like(read_toml(EXAMPLES / "rice_hoe_reverse.toml"))
    data["trajectory"]["points"] = data["trajectory"]["points"][:3]
    with pytest.raises(ProblemError, match=r"trajectory\.points = \[\[.*\]\]: expected at least 4 points"):
        reverse.parse_problem(data)
    data = numpy_like(read_toml(EXAMPLES / "gear_limacon.toml"))
    data["pair"]["driven_order"] = np.float64(2.5)
    with pytest.raises(ProblemError, match=r"pair\.driven_order = 2\.5: expected a whole number"):
        gears.parse_problem(data)
    data["pair"]["driven_order"] = np.bool_(True)
    with pytest.raises(ProblemError, match=r"pair\.driven_order = True: expected a whole number"):
        gears.parse_problem(data)


def test_version(capsys):
    with pytest.raises(SystemExit) as exit:
        main(["--version"])
    assert exit.value.code == 0
    assert capsys.readouterr().out == f"transplanter {version('transplanter')}\n"


def test_fivebar_plate_angle_beyond_a_turn_is_refused_in_degrees():
    data = read_toml(EXAMPLES / "vegetable_planting.toml")
    data["key_poses"][2]["angle_deg"] = 450.0
    with pytest.raises(ProblemError, match=r"<dict>: key_poses\[\]\.angle_deg = \[113\.8, 100\.0, 450\.0, 89\.2\]: "
                                           r"expected plate directions within one turn"):
        fivebar.parse_problem(data)


def test_write_drawings_takes_a_folder_name_and_writes_millimetre_dxf(tmp_path):
    import ezdxf

    result = gears.synthesize(gears.load_problem(EXAMPLES / "gear_ellipse.toml"))
    written = gears.write_drawings(result, str(tmp_path / "drawings"))
    assert written and all(path.exists() for path in written)
    dxf = [path for path in written if path.suffix == ".dxf"]
    assert dxf and all(ezdxf.readfile(path).header["$INSUNITS"] == 4 for path in dxf)   # 4: millimetres

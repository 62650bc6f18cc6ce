"""Problem classes built in Python (mm and radians) are checked as the files are: a value in degrees, of the
wrong type or out of range is refused with one ProblemError naming the class and the field, never a deep
exception, a hang or a silently different result."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from transplanter import burmester, cam, fivebar, gears, parallelogram, pickup, reverse
from transplanter.cam.problem import Follower, Segment
from transplanter.errors import ProblemError
from transplanter.geometry.dyad import Link
from transplanter.parallelogram.evaluation import problem_design

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _gear():
    return gears.parse_problem({"driver": {"family": "limacon", "base": 50.0, "amplitude": 16.0},
                                "pair": {"driven_order": 2}})


def _cam():
    return cam.load_problem(EXAMPLES / "cam_seedling_support.toml")


def _parallelogram():
    return parallelogram.load_problem(EXAMPLES / "onion_transplanter.toml")


CASES = {
    "gear order below 1 (it looped forever)": (_gear, "driven_order", -1, "GearProblem.driven_order = -1"),
    "gear order as text": (_gear, "driven_order", "2", "a whole number from 1 to 12"),
    "gear teeth not whole": (_gear, "teeth", 30.5, "GearProblem.teeth = 30.5"),
    "gear speed 0": (_gear, "driver_speed", 0.0, "a speed other than 0"),
    "gear driver not a curve": (_gear, "driver", "ellipse", "GearProblem.driver = 'ellipse'"),
    "cam pressure limit in degrees (every cam passed)": (_cam, "pressure_limit", 30.0, "between 0 and pi/2"),
    "cam follower of no kind": (_cam, "follower", Follower("translating_typo", 6.0), "a Follower of kind"),
    "cam negative roller": (_cam, "follower", lambda p: dataclasses.replace(p.follower, roller_radius=-6.0),
                            "follower.roller_radius = -6.0"),
    "cam segment of no kind": (_cam, "segments", (Segment("zzz", 2 * np.pi, "harmonic", 1.0),), "segments[0]"),
    "cam swing in degrees": (_cam, "segments",
                             lambda p: (dataclasses.replace(p.segments[0], lift=36.0),) + p.segments[1:],
                             "segments[0].lift = 36.0"),
    "cam samples as text": (_cam, "samples", "3600", "CamProblem.samples = '3600'"),
    "five-bar design angle in degrees": (lambda: fivebar.load_design(EXAMPLES / "vegetable_planting_table4.toml"),
                                         "carrier_angle", -28.59, "GivenDesign.carrier_angle = -28.59"),
    "five-bar design without a rod": (lambda: fivebar.load_design(EXAMPLES / "vegetable_planting_table4.toml"),
                                      "rod_length_AF", 0.0, "GivenDesign.rod_length_AF = 0.0"),
    "pick-up bend in degrees": (lambda: pickup.load_problem(EXAMPLES / "pickup_forward.toml"), "bend", 150.0,
                                "PickupProblem.bend = 150.0"),
    "pick-up picking misspelt": (lambda: pickup.load_problem(EXAMPLES / "pickup_forward.toml"), "picking", "farthes",
                                 'expected "farthest" or a carrier turn'),
    "onion reference in degrees": (_parallelogram, "conventions",
                                   lambda p: dataclasses.replace(p.conventions, alpha_reference=-90.0),
                                   "conventions.alpha_reference = -90.0"),
    "onion depth band reversed": (_parallelogram, "depth_band", (30.0, 25.0), "0 <= low < high"),
    "onion design missing l5": (_parallelogram, "design", lambda p: {k: v for k, v in p.design.items() if k != "l5"},
                                "a dict of exactly m11, b, l"),
    "onion alpha bounds in degrees": (_parallelogram, "bounds", {"alpha": (0.0, 20.0)}, "bounds['alpha']"),
    "burmester link phases in degrees": (lambda: burmester.load_problem(EXAMPLES / "burmester_4poses.toml"), "link",
                                         Link(np.zeros(2), np.array([0.0, -18.0, -50.0, -90.0])), "within one turn"),
    "burmester labels short": (lambda: burmester.load_problem(EXAMPLES / "burmester_4poses.toml"), "labels", ("a",),
                               "a tuple of 4 names"),
    "reverse direction as a bool": (lambda: reverse.load_problem(EXAMPLES / "rice_hoe_reverse.toml"), "direction", True,
                                    "ReverseProblem.direction = True"),
    "reverse open curve": (lambda: reverse.load_problem(EXAMPLES / "rice_hoe_reverse.toml"), "points",
                           lambda p: p.points[: len(p.points) // 2], "the curve looks open"),
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_a_bad_class_field_is_one_problem_error(name):
    make, field, value, words = CASES[name]
    problem = make()
    value = value(problem) if callable(value) else value
    with pytest.raises(ProblemError, match="expected") as error:
        dataclasses.replace(problem, **{field: value})
    assert words in str(error.value)


def test_numpy_scalars_and_paths_give_plain_json_reports():
    """numpy float32 / int64 values and a Path as the source give the report the file gives (plain JSON)."""
    plain = _gear()
    mixed = dataclasses.replace(plain, driven_order=np.int64(2), driver_speed=np.float32(plain.driver_speed),
                                source=Path("<dict>"))
    assert json.dumps(gears.synthesize(mixed).to_json(), allow_nan=False)
    problem = _cam()
    mixed = dataclasses.replace(problem, base_radius=np.float32(30.0), source=Path(problem.source),
                                follower=dataclasses.replace(problem.follower, arm_length=np.float32(58.0)))
    reports = [cam.synthesize(p).to_json() for p in (problem, mixed)]
    for report in reports:
        report.pop("timings_s")
    assert json.dumps(reports[1], allow_nan=False) == json.dumps(reports[0], allow_nan=False)


def test_numpy_integers_are_taken_where_python_ones_are():
    """A choice given as a numpy integer (a direction +-1 out of an array) is the same choice, stored as the plain
    option (a check of the type alone would refuse np.int64(1))."""
    for problem in (_cam(), reverse.load_problem(EXAMPLES / "rice_hoe_reverse.toml")):
        turned = dataclasses.replace(problem, direction=np.int64(problem.direction))
        assert turned.direction == problem.direction and type(turned.direction) is int


def test_an_onion_design_file_built_in_python_is_checked():
    given = problem_design(_parallelogram())
    with pytest.raises(ProblemError, match=r"DesignFile\.published = .*expected a dict of finite numbers"):
        dataclasses.replace(given, published={"depth_mm": float("nan")})


def test_five_bar_angles_in_radians_warn_as_burmester_poses_do():
    from transplanter.errors import TransplanterWarning
    from transplanter.toml_fields import read_toml

    data = read_toml(EXAMPLES / "vegetable_planting.toml")
    for row in data["key_poses"]:
        row["angle_deg"] = float(np.radians(row["angle_deg"]))
    with pytest.warns(TransplanterWarning, match=r"rad\.toml: key_poses\[\]\.angle_deg .* look like radians"):
        fivebar.parse_problem(data, "rad.toml")


def test_figures_and_drawings_name_a_wrong_result_or_folder(tmp_path):
    """Output functions given a problem instead of a result, or no folder, a file or a path under a file, say so
    in one ProblemError (AttributeError, TypeError or FileExistsError came from deep inside; "" wrote into the
    current folder)."""
    problem = gears.parse_problem({"driver": {"family": "ellipse", "semi_major_axis": 30.0, "eccentricity": 0.3}})
    with pytest.raises(ProblemError, match=r"result = a GearProblem: expected a GearResult"):
        gears.draw_figures(problem)
    for module in (burmester, cam, fivebar, parallelogram, pickup, reverse):
        with pytest.raises(ProblemError, match=r"result = None: expected a \w+"):
            module.draw_figures(None)
    result = gears.synthesize(problem)
    (tmp_path / "file").write_text("")
    for folder, words in ((None, "expected the name of a folder"), ("", "expected the name of a folder"),
                          (tmp_path / "file", "a file is there"), (tmp_path / "file" / "x", "cannot be made")):
        with pytest.raises(ProblemError, match=words):
            gears.write_drawings(result, folder)
    assert [p.name for p in tmp_path.iterdir()] == ["file"]


def assert_pickles_to_the_same_report(result):
    """``result`` goes through pickle and reports the same (its wall times aside)."""
    import pickle

    again = pickle.loads(pickle.dumps(result))
    reports = [r.to_json() for r in (result, again)]
    for report in reports:
        report.pop("timings_s", None)
    assert json.dumps(reports[0]) == json.dumps(reports[1])


@pytest.mark.parametrize("module, example", [(gears, "gear_ellipse.toml"), (gears, "gear_ratio_formula.toml"),
                                             (gears, "gear_ratio.toml"), (reverse, "rice_hoe_reverse.toml"),
                                             (pickup, "pickup_forward.toml")])
def test_results_pickle(module, example, request):
    """A result goes through pickle (ProcessPoolExecutor sweeps send results between processes) and reports the
    same: curves and trains evaluate through classes, not closures (the five-bar's, in test_api; the composite
    gear pair's, gear_cusp_composite.toml, in tests/gears/test_composite_teeth.py on the result it tests). The rice
    hoe's is the session's rice_full_result (``reverse.synthesize`` of the file, as here)."""
    if example == "rice_hoe_reverse.toml":
        assert_pickles_to_the_same_report(request.getfixturevalue("rice_full_result"))
    else:
        assert_pickles_to_the_same_report(module.synthesize(module.load_problem(EXAMPLES / example)))

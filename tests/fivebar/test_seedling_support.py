"""The seedling support of Wang et al. 2025 (section 4) timed to the five-bar, against ground truth built here.

The five-bar under test is Wang et al. 2025's Table 4 design evaluated with ``--design`` (its motion is the
relative angle fitted through the key and return points): a real mechanism in milliseconds. The synthesized
example (``example_result``) is used only where a ``FiveBarResult`` is needed (figures, DXF, animation).
"""
import json
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from scipy.optimize import brentq, minimize_scalar

from transplanter import fivebar
from transplanter.cli import main
from transplanter.errors import ProblemError
from transplanter.fivebar.evaluation import evaluate_design, load_design
from transplanter.fivebar.report import support_json
from transplanter.fivebar.support import design_support
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/vegetable_planting_support.toml"
PLAIN = ROOT / "examples/vegetable_planting.toml"
TABLE4 = ROOT / "examples/vegetable_planting_table4.toml"


def _problem(**support_changes):
    data = read_toml(EXAMPLE)
    data["support"].update(support_changes)
    for key in [k for k, v in support_changes.items() if v is None]:
        del data["support"][key]
    return fivebar.parse_problem(data, "support.toml")


@pytest.fixture(scope="module")
def problem():
    return fivebar.load_problem(EXAMPLE)


@pytest.fixture(scope="module")
def evaluation(problem):
    return evaluate_design(problem, load_design(TABLE4))


@pytest.fixture(scope="module")
def support(evaluation):
    return evaluation.support


def _forward(evaluation, turns):
    """P and E from the linkage's own circle intersections (``FiveBar.forward``), not ``close_loop``."""
    relative = evaluation.candidate.relative_angle
    return evaluation.mech.forward(turns, relative.evaluate(turns))


def _nearest_turn(evaluation, point, guess):
    """Carrier turn (rad) at which P passes nearest ``point``, searched about ``guess`` by forward kinematics."""
    result = minimize_scalar(lambda c: np.linalg.norm(_forward(evaluation, np.array([c]))["p"][0] - point),
                             bounds=(guess - 0.3, guess + 0.3), method="bounded", options={"xatol": 1e-10})
    return result.x, result.fun


def test_segments_are_the_design_stages_found_by_forward_kinematics(problem, evaluation, support):
    """Push ends at the last key pose; receive ends where P passes the first return point; return ends where it
    passes the last one. The return points' turns are found here by minimising |P - point| along the motion."""
    grid = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    p = _forward(evaluation, grid)["p"]
    turns = []
    for point in problem.return_points[[0, -1]]:
        guess = grid[np.nanargmin(np.linalg.norm(p - point, axis=1))]
        turn, miss = _nearest_turn(evaluation, point, guess)
        assert miss < problem.return_tolerance_mm
        turns.append(turn)
    marks = np.degrees([0.0, problem.carrier_turns[-1], *turns, 2 * np.pi])
    cam = [np.degrees(s.angle) for s in support.cam.problem.segments]
    assert np.allclose(cam, np.diff(marks), atol=1e-5)
    assert [s.kind for s in support.cam.problem.segments] == ["rise", "dwell", "return", "dwell"]
    assert support_json(support)["segments"]["source"].startswith("design stages")


def _rocker_angle(linkage, height, guess):
    """theta_CG that closes C-G-H at plate height ``height``, by bracketing |G - H| - l_GH near ``guess``."""
    h = np.array([linkage.plate_x, height + linkage.plate_length])

    def gap(theta):
        return np.hypot(*(linkage.pivot + linkage.rocker_length * np.array([np.cos(theta), np.sin(theta)]) - h)) \
            - linkage.rod_length
    grid = guess + np.linspace(-0.3, 0.3, 601)
    values = np.array([gap(t) for t in grid])
    k = np.flatnonzero(np.sign(values[:-1]) != np.sign(values[1:]))
    k = k[np.argmin(np.abs(grid[k] - guess))]
    return brentq(gap, grid[k], grid[k + 1], xtol=1e-13)


def test_swing_from_eq14_solved_independently(support):
    spec = support.spec
    low = _rocker_angle(spec.linkage, spec.heights[0], spec.low_angle)
    high = _rocker_angle(spec.linkage, spec.heights[1], spec.high_angle)
    assert low == pytest.approx(spec.low_angle, abs=1e-9)
    assert high == pytest.approx(spec.high_angle, abs=1e-9)
    assert support_json(support)["swing_deg"] == pytest.approx(np.degrees(low - high), abs=1e-7)
    assert support.cam.problem.segments[0].lift == pytest.approx(abs(low - high), abs=1e-9)


def test_plate_height_follows_the_cam_through_eq14(support):
    """The follower's swing (the cam tool's own displacement column) turns C-G; H is where the circle of radius
    l_GH about G meets x = x_Z; Z is l_HZ below H. The plate is low on the rest, high on the receive."""
    spec, linkage = support.spec, support.spec.linkage
    cam = support.cam.geometry
    swing = np.interp(support.carrier_turns, cam.angle, cam.motion[0])     # cam angle = carrier turn (ratio 1)
    rocker = spec.low_angle + np.sign(spec.high_angle - spec.low_angle) * swing
    g = linkage.pivot + linkage.rocker_length * np.column_stack([np.cos(rocker), np.sin(rocker)])
    side = np.sign(spec.heights[0] + linkage.plate_length - g[0, 1])          # H above or below G at pose 1
    h_y = g[:, 1] + side * np.sqrt(linkage.rod_length**2 - (linkage.plate_x - g[:, 0]) ** 2)
    scale = linkage.rocker_length
    assert np.allclose(support.plate_height, h_y - linkage.plate_length, atol=1e-9 * scale)
    stage = np.searchsorted(np.cumsum(support.stages), support.carrier_turns, side="right")
    assert np.allclose(support.plate_height[stage == 1], spec.heights[1], atol=1e-9 * scale)
    assert np.allclose(support.plate_height[stage == 3], spec.heights[0], atol=1e-9 * scale)
    assert np.all(np.diff(support.plate_height[stage == 0]) > 0)
    joints = support.joints(support.carrier_turns[::50])
    assert np.allclose(np.linalg.norm(joints["G"] - joints["H"], axis=1), linkage.rod_length, atol=1e-9 * scale)
    assert np.allclose(np.linalg.norm(joints["K"] - joints["C"], axis=1), spec.follower.arm_length)


def test_roller_rides_the_cam_as_the_support_moves(support):
    """The arm C-K turned with the rocker puts the roller centre on the cam's pitch curve turned with the carrier."""
    turns = support.carrier_turns[::90]
    roller = support.joints(turns)["K"]
    for turn, k in zip(turns, roller, strict=True):
        pitch = support.cam_outline(turn, "pitch")
        assert np.min(np.linalg.norm(pitch - k, axis=1)) < 0.2      # pitch sampled every 0.1 deg, ~0.06 mm apart


def test_clearance_by_direct_sampling(problem, evaluation, support):
    fine = np.linspace(0, 2 * np.pi, 36000, endpoint=False)
    x_e = _forward(evaluation, fine)["e"][:, 0]
    gap = x_e - problem.support.linkage.plate_x
    k = int(np.argmin(gap))
    assert support.clearance_mm == pytest.approx(gap[k], abs=1e-3)
    assert np.degrees(support.clearance_turn) == pytest.approx(np.degrees(fine[k]), abs=0.2)
    report = support_json(support)
    assert report["clearance_to_receiving_plate_mm"] == support.clearance_mm > 0


def test_plate_across_hinge_e_fails_the_check(evaluation):
    """Table 5's x_Z = -130 with its pivot moved along: Table 4's hinge E reaches x = -163, so they collide."""
    moved = _problem(plate_x=-130.0, pivot=[65.4, -80.0], cam_center=[106.36, -16.91])
    result = evaluate_design(moved, load_design(TABLE4))
    fine = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    assert result.support.clearance_mm == pytest.approx(_forward(evaluation, fine)["e"][:, 0].min() + 130, abs=1e-6)
    assert result.support.clearance_mm < 0
    assert any("right of the receiving plate's hinge E" in f for f in result.support.failures)


def test_typed_segments_and_drive_ratio(evaluation):
    typed = evaluate_design(_problem(segments_deg=[110.0, 80.0, 85.0, 85.0]), load_design(TABLE4)).support
    assert [np.degrees(s.angle) for s in typed.cam.problem.segments] == pytest.approx([110, 80, 85, 85])
    assert support_json(typed)["segments"]["source"].startswith("typed")
    with pytest.raises(ProblemError, match=r"support\.drive_ratio = 2\.0: .*720 deg of cam: expected one cam turn "
                                           r"\(360 deg\); with these stages the ratio would be 1$"):
        evaluate_design(_problem(drive_ratio=2.0), load_design(TABLE4))


def test_without_support_nothing_changes(evaluation):
    plain = fivebar.load_problem(PLAIN)
    assert plain.support is None
    report = evaluate_design(plain, load_design(TABLE4)).to_json()
    assert "support" not in report
    with_support = evaluation.to_json()
    assert {k: v for k, v in with_support.items() if k != "support"} == report


@pytest.mark.parametrize("changes, words", [
    ({"colour": "red"}, r"support\.colour = 'red': expected no such field here"),
    ({"segments_deg": [110.0, 80.0, 85.0, 80.0]},
     r"support\.segments_deg = .*adding up to 360 deg \(these add up to 355"),
    ({"plate_x": -90.0}, r"support\.plate_x = -90\.0: expected a line left of the receiving plate's hinge E, which "
                         r"ranges\.x_e puts from x = -100 to 0 mm in pose 1"),
    ({"heights": [-188.0, -307.0]}, r"support\.heights = .*low < high"),
    ({"heights": [-400.0, -188.0]}, r"support\.heights = .*C-G-H closes"),
    ({"heights": [-307.0, -80.0]}, r"support\.assembly = 1: expected an assembly in which H stays on one side of G "
                                   r"between the heights \(with this one the rod G-H passes horizontal, a dead point; "
                                   r"try assembly = -1\)"),
    ({"roller_side": "pushed"}, r"support\.roller_side = 'pushed': expected \"pulled\""),
    ({"arm_length": 5.0}, r"support\.arm_length = 5\.0: expected an arm whose roller reaches the cam"),
    ({"law": "cubic"}, r"support\.law = 'cubic': expected one of"),
    ({"drive_ratio": 0.0}, r"support\.drive_ratio = 0\.0"),
    ({"plate_x": None}, r"support\.plate_x = None"),
])
def test_bad_support_fields_are_named(changes, words):
    with pytest.raises(ProblemError, match=words) as error:
        _problem(**changes)
    assert "\n" not in str(error.value)


def test_dead_point_names_the_assembly_that_has_none():
    """Up to -80 mm assembly 1 swings G past the height of H (the rod passes horizontal); assembly -1 does not."""
    spec = _problem(heights=[-307.0, -80.0], assembly=-1).support
    linkage = spec.linkage
    sides = [np.sign(linkage.slider_point(h)[1] - linkage.joint_g(a)[1])
             for a, h in ((spec.low_angle, -307.0), (spec.high_angle, -80.0))]
    assert sides[0] == sides[1]


def test_cli_design_out_lists_the_cam_files(tmp_path, capsys):
    out = tmp_path / "out"
    code = main(["fivebar", str(EXAMPLE), "--design", str(TABLE4), "--json", "--out", str(out)])
    report = json.loads(capsys.readouterr().out)
    assert code == 1                                       # Table 4's closure margin, not the support
    assert report["failures"] == ["closure: min sin^2(EBF) = 0.0041 < 0.01"]
    files = {name for names in report["files"].values() for name in names}
    assert {"FAILED-cam.dxf", "FAILED-cam.svg", "FAILED-cam_profile.csv"} <= files
    assert files == {p.name for p in out.iterdir()}
    support = report["support"]
    for key in ("swing_deg", "theta_cg_deg", "clearance_to_receiving_plate_mm", "segments", "drive_ratio", "cam"):
        assert key in support
    assert {"max_pressure_angle_deg", "min_curvature_radius_mm", "undercut"} <= set(support["cam"])
    markdown = (out / "FAILED-report.md").read_text()
    assert "## Seedling support" in markdown
    from transplanter.cam.table5 import evaluate_table5
    assert support["table5"] == json.loads(json.dumps(evaluate_table5().to_json()))   # the published support
    assert "Table 5 as printed does not assemble" in markdown and "lifts the plate (pulled)" in markdown


def test_cli_bad_support_exits_2(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(EXAMPLE.read_text().replace("drive_ratio = 1.0", "drive_ratio = 1.0\nspeed = 3"))
    assert main(["fivebar", str(bad), "--design", str(TABLE4)]) == 2
    err = capsys.readouterr().err.strip()
    assert "support.speed" in err and "\n" not in err


def test_support_entities_and_figure(support):
    """In the drawing convention's layers: the chain C-G-H-Z at pose 1, the labels, and the cam's profile and pitch
    curve about D at their own distances from D; the figure draws the plate height the design computed."""
    from transplanter.drawing.sheet import Sheet
    from transplanter.fivebar.drawings import _support_entities
    from transplanter.fivebar.figures import draw_support

    sheet = Sheet()
    _support_entities(support, sheet, 2.0, 5.0)
    entities = list(sheet.space)
    assert {e.dxf.layer for e in entities} == {"CENTERLINES", "BORE", "OUTLINE", "PITCH", "TEXT"}
    assert {e.dxf.text for e in entities if e.dxftype() == "TEXT"} == {"C", "G", "H", "Z", "D"}
    polylines = [np.array(e.get_points("xy")) for e in entities if e.dxftype() == "LWPOLYLINE"]
    joints = {name: points[0] for name, points in support.joints([0.0]).items()}
    assert np.allclose(polylines[0], [joints[n] for n in "CGHZ"])
    d = support.spec.cam_center
    for outline, curve in zip(polylines[1:], ("profile", "pitch"), strict=True):
        expected = np.linalg.norm(getattr(support.cam.geometry, curve), axis=1)
        assert np.allclose(np.linalg.norm(outline - d, axis=1), expected)
    figure = draw_support(support)
    timing = figure.axes[1]
    assert np.allclose(timing.get_lines()[0].get_ydata(), support.plate_height)


def test_drawings_figures_and_animation_show_the_support(example_result, tmp_path):
    """The synthesized example with its support: the support in linkage.dxf, the cam's files, the support figure,
    and animation frames that differ from those without it."""
    from dataclasses import replace

    from transplanter.fivebar.animation import render_frames
    from transplanter.fivebar.drawings import write_drawings

    problem = fivebar.load_problem(EXAMPLE)
    design = example_result.design
    support = design_support(problem.support, design.mech, design.relative_angle, problem.carrier_turns,
                             design.stroke.carrier_turns, problem.source)
    result = replace(example_result, support=support)
    assert support.clearance_mm > 0 and support.passed
    names = {path.name for path in write_drawings(result, tmp_path)}
    assert {"linkage.dxf", "cam.dxf", "cam.svg", "cam_profile.csv"} <= names
    document = ezdxf.readfile(tmp_path / "linkage.dxf")
    space = document.modelspace()
    texts = {e.dxf.text for e in space.query("TEXT")}
    assert {"C", "G", "H", "Z", "D"} <= texts
    joints = {name: points[0] for name, points in support.joints([0.0]).items()}
    chains = [np.array(e.get_points("xy")) for e in space.query('LWPOLYLINE[layer=="CENTERLINES"]') if len(e) == 4]
    assert any(np.allclose(chain, [joints[n] for n in "CGHZ"]) for chain in chains)
    assert any(np.allclose(np.linalg.norm(np.array(p.get_points("xy")) - joints["D"], axis=1).min(),
                           support.cam.base_radius, rtol=1e-3) for p in space.query("LWPOLYLINE"))
    figures = fivebar.draw_figures(result)
    assert {"support", "cam_motion", "cam_profile"} <= set(figures)
    with_support = render_frames(result, frames=2)
    without = render_frames(example_result, frames=2)
    assert with_support[1].tobytes() != without[1].tobytes()

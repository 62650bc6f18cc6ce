"""The toothed planetary train: whole counts against hand-computed circles and on a spline, the carrier
layout, where each gear sits, the rack/shaper choice with its numbers, and bad [gears] input."""
import dataclasses
import math
import os
from pathlib import Path

import numpy as np
import pytest

from transplanter import side_process
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.fivebar.problem import load_problem, parse_problem
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.gears import swept_teeth
from transplanter.gears.pair import arc_lengths
from transplanter.gears.teeth import generate_teeth
from transplanter.trains.planetary import design_train
from transplanter.trains.report import toothed_train_json
from transplanter.trains.rolling import arc_map, conjugate_curve
from transplanter.trains.toothed_train import (
    Gearing,
    cut_stages,
    cutting_reasons,
    design_toothed_train,
    gear_angles,
    stage_shape,
)

CONSTANT_RATE = RelativeAngle(0.3, np.zeros(12))             # rho' = 1: four equal circles of radius a / 2
_K = np.arange(12)
#: A smooth relative angle whose four pitch curves are convex (rho' from 0.69 to 1.3).
SMOOTH = RelativeAngle(0.3, 0.2 * np.sin(2 * np.pi * _K / 12) + 0.1 * np.cos(4 * np.pi * _K / 12))
#: Larger swings: the sun and both gears of stage 2 get concave stretches.
CONCAVE = RelativeAngle(0.3, 0.4 * np.sin(2 * np.pi * _K / 12) + 0.2 * np.cos(4 * np.pi * _K / 12))
CARRIER = 48.15


def _circle_least(alpha_deg: float) -> int:
    """A circle of radius R: perimeter 2 pi R, curvature radius R, so Z >= 2 / sin^2(alpha)."""
    return math.ceil(2 / math.sin(math.radians(alpha_deg)) ** 2)


@pytest.fixture(scope="module")
def circles():
    return design_toothed_train(CONSTANT_RATE, CARRIER, Gearing(), "test")


@pytest.fixture(scope="module")
def smooth():
    return design_toothed_train(SMOOTH, CARRIER, Gearing(), "test")


def test_circles_get_the_hand_counted_teeth(circles):
    """18 teeth at 20 deg (2 / sin^2 = 17.1): a = m Z = 27 mm each, which spans 48.15 mm with the shaft
    bent by arccos(48.15 / 54) at O."""
    assert _circle_least(20) == 18
    assert circles.counts == (18, 18)
    assert circles.train.center_distances == pytest.approx((27.0, 27.0), rel=1e-12)
    assert circles.bend_angle == pytest.approx(math.acos(CARRIER / 54.0), rel=1e-12)
    for gear in circles.gears:
        radius = np.hypot(*gear.pitch_curve.T)
        assert radius == pytest.approx(13.5, rel=1e-12)
        assert gear.convex and gear.cutter == "rack" and gear.teeth == 18
    assert circles.passed, circles.failures


@pytest.mark.parametrize("carrier,alpha,expected", [(100.0, 20.0, (33, 34)), (20.0, 25.0, (12, 12))])
def test_circle_counts_on_other_carriers(carrier, alpha, expected):
    """|OA| = 100: a1 + a2 = 1.5 (Z1 + Z2) >= 100 needs 67 teeth; the largest gear is least when they are split
    33 + 34; at 25 deg a circle
    needs 2 / sin^2(25 deg) = 11.2 -> 12 teeth, and 18 mm each spans a 20 mm carrier."""
    unit = design_train(CONSTANT_RATE, (1.0, 1.0))
    gearing = Gearing(pressure_angle=math.radians(alpha))
    shapes = [stage_shape(d, gearing) for d in (unit.stage_one, unit.stage_two)]
    assert [s.min_teeth for s in shapes] == [_circle_least(alpha)] * 2
    assert [s.perimeter for s in shapes] == pytest.approx([np.pi, np.pi], rel=1e-12)
    from transplanter.trains.toothed_train import _bent_counts
    assert _bent_counts(shapes, 1.5, carrier) == expected


def test_straight_carrier_takes_only_a_module_that_fits():
    """a1 + a2 = |OA| = 100 mm with circles: m (Z1 + Z2) = 100. Module 2 fits (25 + 25); 1.5 does not,
    and the refusal offers 100/67 and 100/66 to 12 digits."""
    t = design_toothed_train(CONSTANT_RATE, 100.0, Gearing(module=2.0, layout="straight"), "test")
    assert t.counts == (25, 25) and t.bend_angle == 0.0
    assert sum(t.train.center_distances) == pytest.approx(100.0, rel=1e-15)
    assert t.shaft == pytest.approx([50.0, 0.0])
    nearest = r"module = 1.49253731343 \(Z = 33, 34\); module = 1.51515151515 \(Z = 33, 33\)"
    with pytest.raises(ProblemError, match=r"gears.module = 1.5 with gears.layout = \"straight\".*" + nearest):
        design_toothed_train(CONSTANT_RATE, 100.0, Gearing(layout="straight"), "test")


def test_whole_counts_and_layout_on_a_spline(smooth):
    """Each gear's pitch perimeter is pi m Z to 1e-9 (drivers from their curves, driven gears from their
    conjugates built by ``trains.rolling``, integrated on their own); the outline-frame pitch curves agree
    to the polyline's accuracy; the shaft is a1 from O and a2 from A; the counts are the least without
    undercut (one fewer would undercut)."""
    m = smooth.module
    a1, a2 = smooth.train.center_distances
    curves = []
    for stage, a in zip((smooth.train.stage_one, smooth.train.stage_two), (a1, a2), strict=True):
        curves += [stage.driver, conjugate_curve(stage.driver, a)]
    for gear, curve in zip(smooth.gears, curves, strict=True):
        assert arc_map(curve).total == pytest.approx(np.pi * m * gear.teeth, rel=1e-9)
        closed = np.r_[gear.pitch_curve, gear.pitch_curve[:1]]
        assert arc_lengths(closed)[-1] == pytest.approx(np.pi * m * gear.teeth, rel=1e-7)
    assert np.hypot(*smooth.shaft) == pytest.approx(a1, rel=1e-12)
    assert np.hypot(*(smooth.shaft - [CARRIER, 0.0])) == pytest.approx(a2, rel=1e-12)
    assert abs(a1 - a2) <= CARRIER <= a1 + a2
    limit = m / np.sin(np.radians(20)) ** 2
    for stage, z in zip((smooth.train.stage_one, smooth.train.stage_two), smooth.counts, strict=True):
        smallest = min(r[c > 0].min() for c, r in zip(stage.convexity, stage.curvature_radius, strict=True))
        assert smallest >= limit
        assert smallest * (z - 1) / z < limit                     # the count is the least that clears it
    assert smooth.passed, smooth.failures


def test_gears_touch_on_their_lines_of_centres_as_placed(smooth):
    """Placed by ``gear_angles`` at any carrier turn, each pair's pitch curves reach the line of centres
    at radii adding up to the centre distance (which fixes the handedness of each stage); the planet
    turns by rho(c) - rho(0)."""
    gears, a = smooth.gears, smooth.train.center_distances
    turns = np.radians([0.0, 37.0, 123.0, 250.0])
    angles = gear_angles(smooth, turns)
    assert angles[0] == pytest.approx([g.angle_at_turn_zero for g in gears], abs=1e-12)
    assert angles[:, 3] - angles[0, 3] == pytest.approx(SMOOTH.evaluate(turns) - SMOOTH.evaluate(0.0), abs=1e-9)

    def radius_toward(gear, angle, direction):
        local = np.arctan2(gear.pitch_curve[:, 1], gear.pitch_curve[:, 0])
        order = np.argsort(local)
        return np.interp(np.mod(direction - angle + np.pi, 2 * np.pi) - np.pi, local[order],
                         np.hypot(*gear.pitch_curve[order].T), period=2 * np.pi)

    for stage in (0, 1):
        driver, driven = gears[2 * stage], gears[2 * stage + 1]
        line = np.arctan2(*(driven.center - driver.center)[::-1])
        for k in range(len(turns)):
            touch = radius_toward(driver, angles[k, 2 * stage], line) + radius_toward(driven, angles[k, 2 * stage + 1],
                                                                                    line + np.pi)
            assert touch == pytest.approx(a[stage], rel=1e-6)


def test_report_json(smooth):
    report = toothed_train_json(smooth)
    assert [g["name"] for g in report["gears"]] == ["sun", "first intermediate", "second intermediate", "planet"]
    assert [g["teeth"] for g in report["gears"]] == [smooth.counts[0]] * 2 + [smooth.counts[1]] * 2
    assert {"max_overlap_mm", "min_clearance_mm", "transmission_error_deg", "passed"} <= set(report["mesh_check"])
    assert report["mesh_check"]["passed"] is True
    assert all(g["module"] == 1.5 and g["cutter"] == "rack" for g in report["gears"])


@pytest.mark.parametrize("cutter", ["rack", "shaper"])
@pytest.mark.parametrize("cores", ["two", "one", "two, the side process refused"])
def test_both_stages_cut_by_twin_processes_are_each_cut_alone(smooth, cores, cutter, monkeypatch):
    """With a second core both stages are cut here and in a side process at once, each envelope (of a shaper and
    of the teeth it cuts) shared between the two; on one core, or where the system refuses the process, all here.
    Either way each stage's outlines equal those of cutting it alone in one process, in the stages' order (theirs
    differ, so a swap would show)."""
    monkeypatch.setattr(side_process, "usable_cores", lambda: 1 if cores == "one" else 2)
    if cores.endswith("refused"):       # a sandbox without semaphores or fork
        def refused(*args, **kwargs):
            raise OSError(38, "Function not implemented")
        monkeypatch.setattr(side_process, "ProcessPoolExecutor", refused)
    stages = (smooth.train.stage_one, smooth.train.stage_two)
    alone = [generate_teeth(stage, smooth.module, smooth.pressure_angle, "test", cutter, Gearing().shaper_teeth)
             for stage in stages]
    assert alone[0].counts != alone[1].counts
    cut = cut_stages(stages, smooth.module, smooth.pressure_angle, (cutter, cutter), Gearing().shaper_teeth, "test")
    for mine, expected in zip(cut, alone, strict=True):
        assert mine.counts == expected.counts
        assert all(np.array_equal(a, b) for a, b in zip(mine.outlines, expected.outlines, strict=True))


def test_an_error_of_the_side_process_is_raised_here(smooth, monkeypatch):
    """Where the side process fails in an envelope, this process raises its error (class and message) where the
    two would have swapped their halves, instead of waiting for them."""
    monkeypatch.setattr(side_process, "usable_cores", lambda: 2)
    here, envelope = os.getpid(), swept_teeth._lower_envelope

    def failing_there(*args):
        if os.getpid() != here:
            raise InfeasibleError("the side process could not cut")
        return envelope(*args)

    monkeypatch.setattr(swept_teeth, "_lower_envelope", failing_there)
    stages = (smooth.train.stage_one, smooth.train.stage_two)
    with pytest.raises(InfeasibleError, match="the side process could not cut"):
        cut_stages(stages, smooth.module, smooth.pressure_angle, ("shaper", "shaper"), Gearing().shaper_teeth, "test")


def test_concave_stretch_sends_a_stage_to_the_shaper_with_the_numbers():
    unit = design_train(CONCAVE, (1.0, 1.0))
    gearing = Gearing()
    shapes = [stage_shape(d, gearing) for d in (unit.stage_one, unit.stage_two)]
    assert [s.cutter for s in shapes] == ["shaper", "shaper"]
    sun_hollow = shapes[0].concave_radius[0]
    assert np.isfinite(sun_hollow) and np.isinf(shapes[0].concave_radius[1])
    # a1 = pi m Z1 / P1: the 16-tooth shaper's pitch radius 8 m must fit the sun's hollow a1 kappa, and the
    # convex stretches stay above m / sin^2(alpha); Z1 is the least count doing both
    shape = shapes[0]

    def cuttable(z):
        a_per_module = np.pi * z / shape.perimeter
        return a_per_module * sun_hollow > 8 and a_per_module * shape.convex_radius >= 1 / np.sin(np.radians(20)) ** 2

    assert cuttable(shape.min_teeth) and not cuttable(shape.min_teeth - 1)
    driver, driven = cutting_reasons(unit, 0, "shaper", gearing, 1.5)
    assert driver.startswith("the sun's pitch curve is concave: convexity r^2 + 2 r'^2 - r r'' = -")
    assert "carrier turn" in driver and "a rack cannot cut a hollow" in driver and "16-tooth shaper" in driver
    assert driven.endswith("cut as the envelope of the sun's teeth in the designed motion")
    assert stage_shape(unit.stage_one, Gearing(cutter="shaper")).cutter == "shaper"


def test_given_center_distances_must_give_whole_teeth(circles):
    """a = 27 mm gives 18 circles' teeth of module 1.5; 26 mm gives 17.33 and is refused with 17 and 18 teeth
    (17 would undercut, so 18 and 19)."""
    fixed = design_toothed_train(CONSTANT_RATE, CARRIER, Gearing(center_distances=(27.0, 28.5)), "test")
    assert fixed.counts == (18, 19)
    with pytest.raises(ProblemError, match=r"gears.first_center_distance = 26: gives 17.3333 teeth at module 1.5; "
                                           r"expected whole teeth: 18 at 27 mm or 19 at 28.5 mm"):
        design_toothed_train(CONSTANT_RATE, CARRIER, Gearing(center_distances=(26.0, 27.0)), "test")
    with pytest.raises(ProblemError, match=r"gears center distances \[27, 90\] mm: expected \|a1 - a2\| <= \|OA\|"):
        design_toothed_train(CONSTANT_RATE, CARRIER, Gearing(center_distances=(27.0, 90.0)), "test")


def _with_gears(**gears):
    data = {"key_poses": [{"x": float(t), "y": 0.0, "angle_deg": 0.0, "carrier_turn_deg": t} for t in (0, 18, 50, 90)],
            "return_points": [{"x": 1.0, "y": 1.0}], "gears": gears}
    return parse_problem(data, "p.toml")


def test_gears_table_defaults_and_example():
    gearing = load_problem(Path(__file__).parents[2] / "examples/vegetable_planting.toml").gearing
    assert (gearing.module, gearing.cutter, gearing.layout) == (1.5, "rack", "bent")
    assert gearing.pressure_angle == pytest.approx(np.radians(20))
    g = _with_gears(module=2, pressure_angle_deg=25, cutter="shaper", shaper_teeth=20, layout="straight").gearing
    assert (g.module, g.cutter, g.shaper_teeth, g.layout) == (2.0, "shaper", 20, "straight")


@pytest.mark.parametrize("gears,message", [
    ({"module": 0}, r"p.toml: gears.module = 0.0: expected a module from 0.2 to 10 mm"),
    ({"module": 50.0}, r"gears.module = 50.0: expected a module from 0.2 to 10 mm"),
    ({"pressure_angle_deg": 10}, r"gears.pressure_angle_deg = 10.0: expected an angle from 14.5 to 30 deg"),
    ({"pressure_angle_deg": 0.35}, r"gears.pressure_angle_deg = 0.35: expected an angle from 14.5 to 30 deg"),
    ({"cutter": "hob"}, r"gears.cutter = 'hob': expected \"rack\" or \"shaper\""),
    ({"layout": "curved"}, r"gears.layout = 'curved': expected \"bent\" or \"straight\""),
    ({"shaper_teeth": 3}, r"gears.shaper_teeth = 3: expected a whole number from 8 to 200"),
    ({"shaper_teeth": 16.5}, r"gears.shaper_teeth = 16.5: expected a whole number from 8 to 200"),
    ({"first_center_distance": 30.0}, r"gears = .*first_center_distance.*: expected both"),
    ({"hob": 1}, r"gears.hob = 1: expected no such field here"),
])
def test_bad_gears_input_is_refused_in_one_line(gears, message):
    with pytest.raises(ProblemError, match=message) as error:
        _with_gears(**gears)
    assert "\n" not in str(error.value)


def test_gearing_built_in_python_is_checked():
    with pytest.raises(ProblemError, match=r"Gearing.pressure_angle = 20.0: expected an angle from 14.5 to 30 deg"):
        Gearing(pressure_angle=20.0)
    with pytest.raises(ProblemError, match=r"Gearing.layout = 'zigzag'"):
        Gearing(layout="zigzag")


def test_a_module_that_gives_too_many_teeth_is_refused_before_cutting():
    """On a bent carrier the gears come out near |OA| / 2 across, so about |OA| / (2 m) teeth: a carrier 1000 times
    longer at module 10 would shaper-cut about 2400, past the gear command's cap of 1000 (the same rule holds
    rack-cut gears to 20000); refused before any tooth is cut."""
    with pytest.raises(ProblemError, match=r"gears.module = 10: gives \d+ teeth on the sun \(shaper-cut\); "
                                           r"expected at most 1000 .* 10 is the coarsest module taken"):
        design_toothed_train(CONCAVE, CARRIER * 1000, Gearing(module=10.0), "test")


def test_a_carrier_too_short_at_the_finest_module_says_so():
    with pytest.raises(Exception, match="0.2 is the finest module taken: the mechanism is too small for cut teeth"):
        design_toothed_train(SMOOTH, CARRIER / 1000, Gearing(module=0.2), "test")


def test_a_tooth_outline_that_crosses_itself_fails_the_train_and_is_reported(smooth):
    stage_one, stage_two = smooth.teeth
    crossed = dataclasses.replace(smooth, teeth=(dataclasses.replace(stage_one, self_intersections=(0, 2)), stage_two))
    assert smooth.self_intersections == (0, 0, 0, 0) and smooth.passed
    assert crossed.self_intersections == (0, 2, 0, 0)
    assert crossed.failures == ["first intermediate: its tooth outline crosses itself (2 crossings)"]
    assert not crossed.passed and crossed.mesh_failures == []
    report = toothed_train_json(crossed)
    assert [g["self_intersections"] for g in report["gears"]] == [0, 2, 0, 0]
    assert report["mesh_check"]["passed"] is True and report["mesh_check"]["failures"] == []

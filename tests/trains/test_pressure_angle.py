"""The gear pressure angle of the planetary train over the turn, against the gear library's own pitch curves
and tooth outlines, and its bound as NLP rows."""
import json

import casadi as ca
import numpy as np
import pytest
from matplotlib.figure import Figure

from transplanter._generated.train_pitch_tangent import train_pitch_tangent
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.gears.pair import driven_angle
from transplanter.gears.teeth import generate_teeth
from transplanter.generated import numpy_twin
from transplanter.geometry.periodic_bspline import basis_matrix, knots
from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.turn_quadrature import panels
from transplanter.solve import NLPBuilder, Solver
from transplanter.trains.figures import draw_pressure_angles
from transplanter.trains.planetary import correction_factor, design_train
from transplanter.trains.pressure_angle import (
    PRESSURE_GAP,
    STAGES,
    pressure_excess,
    pressure_rows,
    stage_leans,
    stage_pressure_angles,
)
from transplanter.trains.toothed_train import Gearing

tangent = numpy_twin(train_pitch_tangent)
FINE = np.linspace(0, TWO_PI, 7200, endpoint=False)


def _relative(seed: int, spread: float) -> RelativeAngle:
    rng = np.random.default_rng(seed)
    return RelativeAngle(0.4, np.r_[0.0, rng.normal(0, spread, 11)])


def _stage_turns(train):
    """Carrier turns of each stage's samples: the sun's angle is the carrier turn; the second intermediate's is
    psi(c), inverted as the library wraps it."""
    return train.stage_one.phi1, train.intermediate_turn.inverse(np.mod(train.stage_two.phi1, TWO_PI))


def test_a_constant_ratio_gives_the_nominal_pressure_angle_all_round():
    """rho' = 1: four circles, no lean, the teeth's own angle on both flanks of both meshes, exactly."""
    relative = RelativeAngle(0.3, np.zeros(12))
    gearing = Gearing(pressure_angle=np.radians(25.0), max_pressure_angle=np.radians(40.0))
    pressure = stage_pressure_angles(relative, correction_factor(relative), gearing, FINE)
    assert np.all(pressure.leans == 0.0)
    assert np.all(pressure.flanks == gearing.pressure_angle) and np.all(pressure.largest == gearing.pressure_angle)
    assert pressure.passed


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_derived_lean_is_the_tangent_of_the_gear_library_pitch_curves(seed):
    """Ground truth: ``design_train`` builds the four curves (the drivers from the ratio, the mates as conjugates
    through the gear-pair library). At each sampled contact, atan(r_theta / r) by the library's own slopes, and by
    central differences of its driver radius against its driver angle and of its driven radius a - r1 against its
    driven angle (``driven_angle``), equals the derived lean, whatever a1 and a2; the driven curve's is the
    driver's with the opposite sign. (The differences straddle the knots, where r'' jumps: h times the jump.)"""
    relative = _relative(seed, 0.12)
    rng = np.random.default_rng(seed)
    train = design_train(relative, tuple(rng.uniform(15.0, 40.0, 2)))
    k, h = train.correction, 1e-6
    for stage, turns, (driver_row, driven_row) in zip((train.stage_one, train.stage_two), _stage_turns(train),
                                                      ((0, 1), (2, 3)), strict=True):
        _, derived = tangent([relative.evaluate(turns, 1), relative.evaluate(turns, 2)], [np.full_like(turns, k)])
        r, r_theta, _ = stage.driver.evaluate(stage.phi1)
        assert np.abs(derived[driver_row] - np.arctan(r_theta / r)).max() < 1e-12
        assert np.abs(derived[driven_row] - np.arctan(stage.driven_slope / stage.radius[1])).max() < 1e-12
        rise = stage.driver.evaluate(stage.phi1 + h)[0] - stage.driver.evaluate(stage.phi1 - h)[0]
        driven_turn = driven_angle(stage, stage.phi1 + h) - driven_angle(stage, stage.phi1 - h)
        assert np.abs(derived[driver_row] - np.arctan(rise / (2 * h) / r)).max() < 1e-5
        assert np.abs(derived[driven_row] - np.arctan(-rise / driven_turn / stage.radius[1])).max() < 1e-5
        assert np.array_equal(derived[driven_row], -derived[driver_row])
        assert np.ptp(derived[driver_row]) > np.radians(20)           # curves that lean both ways, and far
        assert np.array_equal(stage_leans(relative, k, turns)[driver_row // 2], derived[driver_row])


def _pitch_crossings(outline: np.ndarray, pitch_radius):
    """Where a closed tooth outline crosses its pitch curve: the polar angle and the outline's outward normal."""
    closed = np.vstack([outline, outline[:1]])
    area = np.sum(closed[:-1, 0] * np.diff(closed[:, 1]) - closed[:-1, 1] * np.diff(closed[:, 0]))
    gap = np.hypot(*closed.T) - pitch_radius(np.mod(np.arctan2(closed[:, 1], closed[:, 0]), TWO_PI))
    crossing = np.flatnonzero(np.sign(gap[:-1]) != np.sign(gap[1:]))
    share = gap[crossing] / (gap[crossing] - gap[crossing + 1])
    points = closed[crossing] + share[:, None] * (closed[crossing + 1] - closed[crossing])
    edges = closed[crossing + 1] - closed[crossing]
    normals = np.sign(area) * np.c_[edges[:, 1], -edges[:, 0]] / np.linalg.norm(edges, axis=1, keepdims=True)
    return np.mod(np.arctan2(points[:, 1], points[:, 0]), TWO_PI), normals


def test_drive_and_coast_flanks_of_rack_cut_teeth_push_at_the_derived_pressure_angles():
    """Ground truth: the rack-cut outline of each stage's driver (``gears.teeth``). Where a flank crosses the pitch
    curve, its outward normal is the line the teeth push along when that point is the contact; the driver turns
    clockwise in its pair's frame (``design_pair``), so there its motion is -e_theta. A flank facing the motion
    (the drive flank) pushes at alpha0 - mu from it, a flank facing away (coast) at alpha0 + mu: 80 of each per
    stage, to the outline's polygon accuracy, against the other sign's error of several degrees."""
    relative = _relative(3, 0.015)                      # convex curves: a rack cuts them
    unit = design_train(relative, (1.0, 1.0))
    module, count, alpha = 1.0, 80, np.radians(20.0)
    train = design_train(relative, tuple(np.pi * module * count / s.perimeters[0] for s in (unit.stage_one,
                                                                                           unit.stage_two)))
    gearing = Gearing(pressure_angle=alpha)
    for index, stage in enumerate((train.stage_one, train.stage_two)):
        outline = generate_teeth(stage, module, alpha, "test", "rack").outlines[0]
        angle, normals = _pitch_crossings(outline, lambda phi, s=stage: s.driver.evaluate(phi)[0])
        motion = np.c_[np.sin(angle), -np.cos(angle)]
        facing = np.einsum("ij,ij->i", normals, motion)
        turns = angle if index == 0 else train.intermediate_turn.inverse(angle)
        drive, coast = stage_pressure_angles(relative, train.correction, gearing, turns).flanks[index]
        forward = facing > 0
        assert forward.sum() == count and (~forward).sum() == count
        measured = np.arccos(np.abs(facing))
        assert np.abs(measured[forward] - drive[forward]).max() < 2e-3
        assert np.abs(measured[~forward] - coast[~forward]).max() < 2e-3
        assert np.abs(measured[forward] - coast[forward]).max() > 0.1


def _derivatives(relative: RelativeAngle, turns: np.ndarray) -> np.ndarray:
    return np.array([relative.evaluate(turns, order) for order in (1, 2, 3)])


def test_pressure_rows_are_the_bound_on_the_numpy_evaluation():
    """The CasADi rows (tan mu / tan(limit - alpha0))^2 - 1 agree with the numpy lean, and are <= 0 exactly where
    the numpy excess is <= 0: one condition, two twins."""
    relative = _relative(5, 0.12)
    k = correction_factor(relative)
    gearing = Gearing(max_pressure_angle=np.radians(35.0))
    rows = np.array(ca.DM(pressure_rows(ca.DM(_derivatives(relative, FINE)), k, gearing)))
    leans = stage_leans(relative, k, FINE)
    allowance = gearing.max_pressure_angle - gearing.pressure_angle
    assert np.abs(rows - ((np.tan(leans) / np.tan(allowance)) ** 2 - 1)).max() < 1e-12
    excess = pressure_excess(leans, gearing)
    assert np.array_equal(rows.max(axis=0) <= 0, excess <= 0)
    assert (excess > 0).any() and (excess <= 0).any()


def test_pressure_rows_hold_a_relative_angle_to_the_limit_in_ipopt():
    """A small NLP: the relative angle nearest a target whose meshes lean too far, with k closing stage 1 (as the
    design NLP has it) and the pressure rows on a 5 deg grid. The fine evaluation of the result reaches the limit
    (the rows bind) and stays within it between grid points to a small fraction of the allowance."""
    target = _relative(5, 0.12)
    gearing = Gearing(max_pressure_angle=np.radians(30.0))
    assert stage_pressure_angles(target, correction_factor(target), gearing, FINE).largest.max() > np.radians(34.0)
    n = target.count
    nlp = NLPBuilder()
    q = ca.vertcat(0, nlp.variables("spline_values", n - 1))
    correction = nlp.variables("correction", lower=0.0)
    grid = np.linspace(0, TWO_PI, 72, endpoint=False)
    slope, bend = (ca.mtimes(ca.DM(basis_matrix(grid, n, order)), q) for order in (1, 2))
    derivatives = ca.horzcat(1 + slope, bend).T
    spans = panels(knots(n), count=n)
    closure = correction * ca.dot(ca.DM(spans.weights.ravel()),
                                  ca.sqrt(1 + ca.mtimes(ca.DM(basis_matrix(spans.nodes.ravel(), n, 1)), q))) - TWO_PI
    nlp.constraints("correction_closure", closure, 0.0, 0.0)
    nlp.constraints("slope", derivatives[0, :].T, 0.1, np.inf)
    nlp.constraints("pressure", pressure_rows(derivatives, correction, gearing).T, -np.inf, 0.0)
    layout = nlp.build(ca.sumsqr(q - target.coefficients))
    solution = Solver("pressure_test", layout).solve({"spline_values": target.coefficients[1:],
                                                      "correction": correction_factor(target)})
    relative = RelativeAngle(target.rho1, np.r_[0.0, solution["spline_values"]])
    assert abs(solution["correction"][0] - correction_factor(relative)) < 1e-10
    pressure = stage_pressure_angles(relative, correction_factor(relative), gearing, FINE)
    excess = pressure_excess(pressure.leans, gearing)
    assert -1e-6 < excess.max() <= PRESSURE_GAP
    assert (solution.row("pressure") <= 1e-9).all()


def test_a_stage_above_the_limit_is_named_with_its_number():
    """With the limit between the two stages' largest pressure angles, exactly the higher stage fails, and the
    message gives its largest angle, the carrier turn and flank where it occurs, and the field it breaks."""
    relative = _relative(2, 0.12)
    k = correction_factor(relative)
    largest = stage_pressure_angles(relative, k, Gearing(), FINE).largest
    high = int(np.argmax(largest))
    assert abs(largest[0] - largest[1]) > np.radians(0.5)
    limit = float(largest.mean())
    pressure = stage_pressure_angles(relative, k, Gearing(max_pressure_angle=limit), FINE)
    worst = np.argmax(pressure.flanks[high].max(axis=0))
    flank = ("drive", "coast")[int(pressure.flanks[high][1, worst] > pressure.flanks[high][0, worst])]
    assert pressure.failures() == [
        f"stage {STAGES[high]}: largest pressure angle {np.degrees(largest[high]):.2f} deg ({flank} flank) at carrier "
        f"turn {np.degrees(FINE[worst]):.1f} deg, above gears.max_pressure_angle_deg = {np.degrees(limit):g}"]
    assert not pressure.passed
    within = float(largest[high]) - PRESSURE_GAP * (float(largest[high]) - Gearing().pressure_angle) / 2
    assert stage_pressure_angles(relative, k, Gearing(max_pressure_angle=within), FINE).passed


def test_report_fields_and_figure_show_each_stage_largest_and_where():
    relative = _relative(1, 0.12)
    pressure = stage_pressure_angles(relative, correction_factor(relative), Gearing(), FINE)
    fields = json.loads(json.dumps(pressure.to_json()))
    assert fields["gear_pressure_angle_stages"] == list(STAGES)
    assert np.allclose(fields["gear_pressure_angle_max_deg"], np.degrees(pressure.flanks.max(axis=(1, 2))))
    for stage in range(2):
        at = np.isclose(np.degrees(FINE), fields["gear_pressure_angle_max_at_deg"][stage])
        flank = ("drive", "coast").index(fields["gear_pressure_angle_max_flank"][stage])
        assert np.isclose(np.degrees(pressure.flanks[stage, flank][at]), fields["gear_pressure_angle_max_deg"][stage])
    assert (fields["gear_pressure_angle_nominal_deg"], fields["gear_pressure_angle_limit_deg"]) == (20.0, 45.0)
    sentence = pressure.summary()
    for stage, value in zip(STAGES, fields["gear_pressure_angle_max_deg"], strict=True):
        assert f"{stage} {value:.2f} deg" in sentence
    ax = Figure().subplots()
    draw_pressure_angles(ax, pressure)
    marker = next(line for line in ax.get_lines() if line.get_label() == "largest of each stage")
    assert np.allclose(marker.get_xydata(), np.c_[fields["gear_pressure_angle_max_at_deg"],
                                                  fields["gear_pressure_angle_max_deg"]])
    assert len(ax.get_lines()) == 2 * 2 + 1 + 2


@pytest.mark.parametrize("limit", [np.radians(20.0), np.radians(10.0), np.pi / 2, np.nan, "45"])
def test_gearing_refuses_a_limit_outside_the_nominal_angle_and_a_right_angle(limit):
    from transplanter.errors import ProblemError

    with pytest.raises(ProblemError, match=r"Gearing\.max_pressure_angle = .*expected an angle above pressure_angle"):
        Gearing(max_pressure_angle=limit)

"""The design NLP maximises the smallest transmission quality; each result is checked here by forward kinematics
and plain geometry, not by the NLP's own variables."""
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from transplanter.errors import ProblemError, SolverError
from transplanter.fivebar.design_solver import CURVATURE_GAP, DesignSolver
from transplanter.fivebar.nlp import CONCAVITY_LIMIT, CURVATURE_BLOCKS, RETURN_TOLERANCE, build_nlp
from transplanter.fivebar.problem import FiveBarProblem, parse_problem
from transplanter.fivebar.region import solution_region
from transplanter.fivebar.whole_turn import CHECK_POINTS, CURVES
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.toml_fields import read_toml
from transplanter.trains.planetary import correction_factor, design_train
from transplanter.trains.toothed_train import Gearing, stage_shape

EXAMPLE = Path(__file__).resolve().parents[2] / "examples/vegetable_planting.toml"
FINE = np.linspace(0, 2 * np.pi, CHECK_POINTS, endpoint=False)


@pytest.fixture(scope="module")
def problem(example_problem):
    return example_problem


@pytest.fixture(scope="module")
def refined(problem):
    """The first region candidate that refines (some stall), its refinement and its attempt at convex curves, as
    the alternatives make them: on one solver, as a lane refines its starts one after another."""
    solver = DesignSolver(problem)
    for start in solution_region(problem).feasible:
        try:
            return start, solver.make_convex(start, solver.refine(start))
        except SolverError:
            continue
    raise AssertionError("no region candidate of the example refines")


@pytest.fixture(scope="module")
def start(refined):
    return refined[0]


@pytest.fixture(scope="module")
def design(refined):
    return refined[1]


def _angle(u, v):
    """Angle between vectors u and v (rows), by atan2 of cross and dot: no closure algebra."""
    return np.abs(np.arctan2(u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0], np.sum(u * v, axis=-1)))


def _triangle_angles(design):
    state = design.mech.forward(FINE, design.relative_angle.evaluate(FINE))
    b, e, f = design.mech.hinge_b, state["e"], state["f"]
    ebf, bef = _angle(e - b, f - b), _angle(b - e, f - e)
    return np.fmin(ebf, np.pi - ebf), np.fmin(bef, np.pi - bef)     # distance from B, E, F in line


def test_the_nlp_maximises_the_smallest_transmission_angle_at_e_and_keeps_the_closure_floor(design, problem):
    """Measured on the hinges of the forward kinematics every 0.05 deg: the angle EBF stays on or above its
    floor (sin^2 >= min_closure_margin, to the exchange's rounding), the reported minima and turns are the
    measured ones, and the NLP's t is sin^2 of the smallest transmission angle at E to the exchange's gap
    (above) and IPOPT's tolerance (below)."""
    ebf, bef = _triangle_angles(design)
    assert np.sin(ebf.min()) ** 2 >= problem.min_closure_margin * (1 - 1e-9)
    assert abs(design.min_angle_ebf - ebf.min()) < 1e-9 and abs(design.min_angle_bef - bef.min()) < 1e-9
    assert FINE[np.argmin(ebf)] == design.min_closure_turn and FINE[np.argmin(bef)] == design.min_angle_bef_turn
    quality = np.sin(bef.min()) ** 2        # t stops within IPOPT's tolerance of the grid's least value
    assert -1e-9 <= (design.quality - quality) / quality <= 1e-3


def test_key_poses_are_exact_and_return_points_within_the_tolerance(design, problem):
    mech, relative = design.mech, design.relative_angle
    state = mech.forward(problem.carrier_turns, relative.evaluate(problem.carrier_turns))
    assert np.abs(state["p"] - problem.poses[:, :2]).max() < 1e-9
    assert np.abs(np.angle(np.exp(1j * (state["direction"] - problem.poses[:, 2])))).max() < 1e-11
    turns = design.stroke.carrier_turns
    reached = mech.forward(turns, relative.evaluate(turns))["p"]
    misses = np.linalg.norm(reached - problem.return_points, axis=1)
    assert misses.max() <= problem.return_tolerance_mm * (1 + 1e-9)
    assert np.allclose(misses, design.return_misses_mm, rtol=0, atol=1e-12)


def test_every_named_active_bound_is_met_by_the_design_and_the_others_are_not(design, problem):
    """Each bound the NLP reports active is checked on the design itself; the ranges left out are inside."""
    active = {(bound.name, bound.side) for bound in design.active_bounds}
    e1, f1 = design.mech.plate_points(problem.poses[0])
    values = {"ep": design.mech.ep, "fp": design.mech.fp, "x_e": e1[0], "x_f": f1[0]}
    for key, (low, high) in problem.ranges.items():
        size = max(abs(low), abs(high))
        for side, bound in (("lower", low), ("upper", high)):
            on = abs(values[key] - bound) <= 1e-6 * size
            assert on == ((f"ranges.{key}", side) in active), (key, side, values[key])
    slope = design.relative_angle.evaluate(FINE, 1)
    if ("ratio", "upper") in active:
        assert 1 / slope.min() == pytest.approx(problem.ratio_bounds[1], rel=1e-4)
    on_tolerance = [j for bound in design.active_bounds if bound.name == RETURN_TOLERANCE for j in bound.entries]
    for j, miss in enumerate(design.return_misses_mm):
        if j in on_tolerance:
            assert miss == pytest.approx(problem.return_tolerance_mm, rel=1e-4)
        else:
            assert miss < problem.return_tolerance_mm * (1 - 1e-6)
    assert (("min_closure_margin", "lower") in active) == (
        design.min_closure_margin <= problem.min_closure_margin * (1 + 1e-6))


def test_pitch_curves_keep_hollows_a_shaper_cuts_by_the_gear_library_curves(design):
    """The example's poses force a concave stretch: the design is held at a kappa >= -CONCAVITY_LIMIT, which
    the gear library's own curves of the design (design_train, signed curvature radii, a = a1, a2) confirm;
    the NLP reports the hold active exactly when the tightest curve's own evaluation sits on it (on the
    example the pressure-angle limit, which bounds the curves' lean, may keep them off it), and the note names
    each curve's least a kappa and the shaper."""
    distances = (24.0, 31.0)
    train = design_train(design.relative_angle, distances)
    library = [float((a / stage.curvature_radius[side]).min())
               for a, stage in zip(distances, (train.stage_one, train.stage_two), strict=True) for side in (0, 1)]
    assert min(library) >= -CONCAVITY_LIMIT * (1 + CURVATURE_GAP)     # the fine check's gap
    # the library samples each curve 721 times; the design's least a kappa is from 7200 turns and the knots' sides
    assert all(sampled >= least - CURVATURE_GAP * CONCAVITY_LIMIT
               for sampled, least in zip(library, design.min_curvature, strict=True))
    assert [value < 0 for value in library] == [value < 0 for value in design.min_curvature]
    assert design.curvature_floor == -CONCAVITY_LIMIT
    tightest = CURVES[int(np.argmin(design.min_curvature))]
    on_hold = min(design.min_curvature) <= -CONCAVITY_LIMIT * (1 - CURVATURE_GAP)
    active = {(b.name, b.side) for b in design.active_bounds}
    assert ((f"a kappa of the {tightest} pitch curve", "lower") in active) == on_hold
    assert "shaper" in design.convexity_note and f"tightest the {tightest}" in design.convexity_note
    assert all(f"{curve} {value:.3f}" in design.convexity_note
               for curve, value in zip(CURVES, design.min_curvature, strict=True))
    assert design.correction == pytest.approx(train.correction, rel=1e-12)


def test_the_shaper_fits_the_hollows_at_the_undercut_free_tooth_counts(design):
    """A hollow no tighter than a / CONCAVITY_LIMIT costs no teeth on the example: the counts the 16-tooth
    shaper's pitch circle needs stay below the undercut-free counts, which set each stage's least count."""
    gearing = Gearing()
    train = design_train(design.relative_angle, (1.0, 1.0))
    for stage in (train.stage_one, train.stage_two):
        shape = stage_shape(stage, gearing)
        undercut_free = np.ceil(ADDENDUM * shape.perimeter / (np.pi * shape.convex_radius
                                                              * np.sin(gearing.pressure_angle) ** 2))
        shaper_fit = np.floor(gearing.shaper_teeth * shape.perimeter / (2 * np.pi * shape.concave_radius[0])) + 1
        assert shape.cutter == "shaper" and shaper_fit < undercut_free == shape.min_teeth


def test_quadrature_of_k_and_the_convexity_switch(problem, start):
    """The NLP's row k int sqrt(rho') dc = 2 pi holds at the library's k (turn_map quadrature); an exchange
    slot's BEF row is sin^2 of the angle BEF by plain geometry, less t; the convexity rows are on by
    default and free when switched off, with no rebuild."""
    nlp = build_nlp(problem, capacity=2)
    layout, values = nlp.layout, nlp.start(start.mech, start.relative_angle, start.stroke, problem.return_points,
                                          problem.poses, problem.carrier_turns)
    assert values["correction"] == correction_factor(start.relative_angle)
    rows = ca.Function("g", [layout.x, layout.p], [layout.g])

    def g_at(turns):
        return np.asarray(rows(layout.vector(values), layout.parameter_vector(
            nlp.parameters(start.mech.branch, turns)))).ravel()

    assert abs(layout.rows["correction_closure"].read(g_at([]))[0]) < 1e-12
    turns = np.radians([33.3, 251.7])
    slots = layout.rows["transmission_quality"].read(g_at(turns))[nlp.fixed_points:nlp.fixed_points + 2]
    state = start.mech.forward(turns, start.relative_angle.evaluate(turns))
    bef = _angle(start.mech.hinge_b - state["e"], state["f"] - state["e"])
    assert np.abs(slots + values["quality"] - np.sin(bef) ** 2).max() < 1e-12
    on = nlp.bounds(0, -CONCAVITY_LIMIT, values["least_curvature"])
    off = nlp.bounds(0, None, values["least_curvature"])
    for name in CURVATURE_BLOCKS:
        grid = layout.rows[name].read(on.lbg)[:nlp.fixed_points]
        assert (grid == 0).all() and np.isneginf(layout.rows[name].read(off.lbg)).all()


def _edited(tolerance):
    data = read_toml(EXAMPLE)
    data["conditions"]["return_tolerance_mm"] = tolerance
    return data


@pytest.mark.parametrize("tolerance", [-0.5, float("nan"), float("inf")])
def test_a_negative_or_non_finite_return_tolerance_is_refused(tolerance):
    with pytest.raises(ProblemError, match=r"conditions\.return_tolerance_mm") as error:
        parse_problem(_edited(tolerance), "f.toml")
    assert "f.toml" in str(error.value)


def test_the_problem_refuses_a_negative_tolerance_given_directly(problem):
    fields = {name: getattr(problem, name) for name in FiveBarProblem.__dataclass_fields__}
    with pytest.raises(ProblemError, match=r"return_tolerance_mm = -1.*>= 0"):
        FiveBarProblem(**{**fields, "return_tolerance_mm": -1.0})

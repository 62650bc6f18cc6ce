"""The five-bar main job, its parts against ground truth, and the published design."""
import json
import re
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from transplanter._generated.fivebar import fivebar_closure_margin
from transplanter.cli import main
from transplanter.errors import InfeasibleError, ProblemError, SolverError
from transplanter.fivebar import design_solver
from transplanter.fivebar.candidate import evaluate_candidate
from transplanter.fivebar.design_solver import DesignSolver, HollowError
from transplanter.fivebar.evaluation import evaluate_design, load_design
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.nlp import CONCAVITY_LIMIT, GRID_BLOCKS, build_nlp
from transplanter.fivebar.problem import parse_problem
from transplanter.fivebar.region import ChainFamily
from transplanter.fivebar.relative_angle import RelativeAngle, fit_relative_angle, negative_intervals
from transplanter.fivebar.return_stroke import solve_return_stroke
from transplanter.fivebar.synthesis import _empty_family, synthesize
from transplanter.generated import numpy_twin
from transplanter.solve import StallRule, relative_violation
from transplanter.toml_fields import read_toml
from transplanter.trains.planetary import printed_correction

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/vegetable_planting.toml"


@pytest.fixture(scope="module")
def problem(example_problem):
    return example_problem


@pytest.fixture(scope="module")
def result(example_result):
    return example_result


@pytest.fixture(scope="module")
def built(problem):
    """The example's design solver, built once for the tests that take a twin of it (``DesignSolver.twin``: the
    state of a new solver, sharing the built Functions)."""
    return DesignSolver(problem)


def test_fitted_relative_angle_interpolates_and_returns_after_a_turn(rng):
    c = np.sort(np.r_[0.0, rng.uniform(0.1, 6.2, 8)])
    rho = 0.3 + c + 0.2 * np.sin(c)
    relative = fit_relative_angle(c, rho, 12)
    assert np.abs(relative.evaluate(c) - rho).max() < 1e-12
    assert abs(relative.evaluate(2 * np.pi) - relative.evaluate(0.0) - 2 * np.pi) < 1e-12


def test_negative_intervals_wrap_around_the_turn():
    turns = np.radians(np.arange(360.0))
    values = np.ones(360)
    values[350:] = values[:5] = values[100:120] = -1
    assert negative_intervals(turns, values) == [(100.0, 119.0), (350.0, 4.0)]


def test_derived_closure_margin_is_sin_squared_of_angle_ebf(rng):
    """The generated margin against the circle intersection of the linkage (no shared algebra)."""
    margin = numpy_twin(fivebar_closure_margin)
    mech = FiveBar(48.0, -0.5, 246.0, np.array([-78.6, -30.1]), 186.0, np.array([99.4, -11.3]),
                   np.array([35.0, -33.1]), -1.0)
    c = rng.uniform(0, 2 * np.pi, 50)
    rho = -1.26 + c
    state = mech.forward(c, rho)
    theta1 = mech.carrier_angle - c
    lengths = [mech.carrier_length, mech.rod_length, mech.link_length, mech.receiving_length, np.hypot(*mech.hinge_b)]
    derived = margin(lengths, [theta1, theta1 + rho, np.full(50, np.arctan2(-30.1, 78.6))])[0]
    assert np.allclose(derived, state["margin"], atol=1e-10)


def test_return_stroke_recovers_a_constructed_mechanism(problem):
    """Ground truth: P of a known five-bar at chosen turns; the IK gets back the turns and relative angles."""
    mech = FiveBar(48.0, -0.5, 246.0, np.array([-78.6, -30.1]), 186.0, np.array([99.4, -11.3]),
                   np.array([35.0, -33.1]), -1.0)
    relative = RelativeAngle(-1.26, np.radians([0, 3, -4, 2, 0, 1, -2, 3, 0, -1, 2, 0]))
    turns = np.radians([150.0, 190.0, 230.0, 270.0, 320.0])
    points = mech.forward(turns, relative.evaluate(turns))["p"]
    key = np.radians(90.0)
    last = mech.forward(np.array([key]), relative.evaluate(np.array([key])))
    stroke = solve_return_stroke(mech, points, key, relative.rho1, float(relative.evaluate(key)),
                                 float(last["direction"][0]))
    assert np.abs(stroke.carrier_turns - turns).max() < 1e-9
    assert np.abs(stroke.relative_angles - relative.evaluate(turns)).max() < 1e-9


def test_main_job_meets_the_key_poses_by_forward_simulation(result, problem):
    check = result.verification
    assert check.key_position_errors_mm.max() < 1e-6
    assert np.abs(check.key_angle_errors_deg).max() < 1e-6
    assert check.roundtrip_max_error_mm < 1e-6
    assert check.contact_gap_mm < 1e-9
    # within the tolerance at the spline's turns; the rolled gears move P by up to their round trip error
    assert check.return_point_errors_mm.max() <= problem.return_tolerance_mm + check.roundtrip_max_error_mm
    assert check.relative_angle_monotonic
    assert check.min_closure_margin >= problem.min_closure_margin - 1e-9
    assert check.min_discriminant > 0
    low, high = problem.ratio_bounds
    assert low <= check.ratio_range[0] and check.ratio_range[1] <= high


def test_main_job_design_keeps_ranges_and_both_chains_close(result, problem):
    mech = result.design.mech
    candidate = evaluate_candidate(problem, mech)
    assert not [d for d in candidate.defects if d.startswith(("ranges", "order", "branch", "crank"))]
    receiving, carrier = mech.joint_chain_errors(problem.poses, problem.carrier_turns)
    assert np.abs(receiving).max() < 1e-9 and np.abs(carrier).max() < 1e-9


def test_exchange_slots_are_the_closure_margin_and_slope_of_forward_kinematics(result, problem):
    """A parametric exchange slot at any carrier turn gives the margin sin^2(EBF) and rho' that the
    independent forward kinematics gives there (less t, for the margin); an unused slot constrains nothing."""
    candidate = result.region.feasible[0]
    nlp = build_nlp(problem, capacity=3)
    layout = nlp.layout
    turns = np.radians([14.2, 123.45])
    values = nlp.start(candidate.mech, candidate.relative_angle, candidate.stroke, problem.return_points,
                       problem.poses, problem.carrier_turns)
    g = ca.Function("g", [layout.x, layout.p], [layout.g])(
        layout.vector(values), layout.parameter_vector(nlp.parameters(candidate.mech.branch, turns)))
    g = np.asarray(g).ravel()
    slots = slice(nlp.fixed_points, nlp.fixed_points + 2)
    forward = candidate.mech.forward(turns, candidate.relative_angle.evaluate(turns))["margin"]
    margin, slope = layout.rows["closure_quality"].read(g)[slots], layout.rows["slope"].read(g)[slots]
    assert np.abs(margin + values["quality"] - forward).max() < 1e-12
    assert np.abs(slope - candidate.relative_angle.evaluate(turns, 1)).max() < 1e-12
    bounds = nlp.bounds(len(turns), -CONCAVITY_LIMIT, -CONCAVITY_LIMIT, closure_in_quality=True)
    for name in GRID_BLOCKS:
        lower, upper = layout.rows[name].read(bounds.lbg), layout.rows[name].read(bounds.ubg)
        assert (np.isfinite(lower[slots]) | np.isfinite(upper[slots])).all()      # a used slot holds its row
        assert np.isneginf(lower[nlp.fixed_points + 2]) and np.isposinf(upper[nlp.fixed_points + 2])


def test_one_solver_serves_every_start_and_round(result, problem):
    """Two refinements (each with its exchange rounds) run on the solver built once; the second start's
    design is the one a freshly built solver gives when offered the same exchange turns. (Offered none, a
    start may end at another local optimum of the max-min: the turns change IPOPT's path, and a start that refined
    in the main job's lanes, offered other turns, may stall offered these: the first that refines is taken.)"""
    first, *others = (result.region.feasible[k] for k in result.chosen.starts)     # starts that refine
    solver = DesignSolver(problem)
    ipopt = solver.solver
    solver.refine(first)
    offered = solver.exchange_turns
    assert offered.size > 0
    for second in others:
        solver.exchange_turns = offered
        try:
            reused = solver.refine(second)
            break
        except HollowError:
            continue
    else:
        pytest.fail("no other start of the chosen design refines offered the first one's exchange turns")
    assert solver.builds == 1 and solver.solver is ipopt
    fresh = DesignSolver(problem)
    fresh.exchange_turns = offered
    same_grid = fresh.refine(second)
    assert abs(reused.objective - same_grid.objective) <= 1e-12 * abs(same_grid.objective)
    for name in ("carrier_length", "rod_length", "receiving_length"):
        assert abs(getattr(reused.mech, name) - getattr(same_grid.mech, name)) < 1e-9
    for name in ("hinge_b", "e_local", "f_local"):
        assert np.abs(getattr(reused.mech, name) - getattr(same_grid.mech, name)).max() < 1e-9


def test_relative_violation_is_the_farthest_row_outside_its_bounds_over_its_size():
    lbg, ubg, scales = np.array([0.0, 1.0, -np.inf]), np.array([0.0, np.inf, 2.0]), np.array([1.0, 0.5, 4.0])
    assert relative_violation(np.array([0.0, 1.5, -7.0]), lbg, ubg, scales) == 0.0
    assert relative_violation(np.array([0.0, 0.9, 3.0]), lbg, ubg, scales) == pytest.approx(0.25)   # (3 - 2) / 4
    assert relative_violation(np.array([-0.3, 0.9, 0.0]), lbg, ubg, scales) == pytest.approx(0.3)
    assert relative_violation(np.array([0.0, np.nan, 0.0]), lbg, ubg, scales) == np.inf


def test_a_solve_held_off_its_bounds_for_the_stall_window_is_stopped_and_says_so(result, problem, monkeypatch):
    """Every iterate of a solve from a region candidate breaks some row by more than 1e-30 of its size, so
    with that as the stall threshold and a window of 3 the solve stops after 3 iterations, and the error
    names the stall, not IPOPT's own status."""
    monkeypatch.setattr(design_solver, "STALL", StallRule(violation=1e-30, iterations=3))
    solver = DesignSolver(problem)
    with pytest.raises(SolverError) as raised:
        solver.solve(result.region.feasible[0])
    watch = solver.solver_for(None).watch       # the solve holds no curvature: the NLP without those rows
    assert watch.count == 3 and watch.stalled
    assert "a stall" in raised.value.status and "100" not in raised.value.status


def test_a_feasible_iterate_restarts_the_stall_count(built):
    solver = built.twin()
    nlp, cap, window = solver.nlp, solver.solver.watch, design_solver.STALL.iterations
    bounds = nlp.bounds(0, -CONCAVITY_LIMIT, -CONCAVITY_LIMIT)
    lbg, ubg = bounds.lbg, bounds.ubg
    cap.watch(None, lbg, ubg, nlp.layout.row_scales())
    order = ca.nlpsol_out()
    inside = np.where(np.isfinite(lbg), lbg, np.fmin(ubg, 0.0))
    outside = np.where(np.isfinite(lbg), lbg - 1.0, ubg + 1.0)

    def iterate(g):
        values = {"g": g, "f": 0.0, "x": np.zeros(nlp.layout.x.shape[0]), "lam_x": np.zeros(nlp.layout.x.shape[0]),
                  "lam_g": np.zeros(len(g))}
        return cap.eval([values.get(name, np.zeros(0)) for name in order])[0]

    assert [iterate(outside) for _ in range(window - 1)] == [0] * (window - 1)
    assert iterate(inside) == 0 and not cap.stalled
    assert [iterate(outside) for _ in range(window)][-1] == 1 and cap.stalled


def test_exchange_beyond_the_solver_room_rebuilds_it_larger(result, built):
    solver = built.twin()
    capacity = solver.nlp.capacity
    design = solver.solve(result.start, np.linspace(0.1, 6.0, capacity + 1), warm=result.design,
                          curvature_floor=-CONCAVITY_LIMIT)
    assert solver.builds == 2 and solver.nlp.capacity == 2 * capacity
    assert design.status == "Solve_Succeeded"


def test_gear_stages_close_and_printed_eq12_does_not(result):
    train = result.train
    assert abs(train.stage_one.closure_error) < 1e-10 and abs(train.stage_two.closure_error) < 1e-10
    k_printed, turn = printed_correction(train.relative_angle)
    # Read as printed, k' = 2 pi / int rho'^(3/2) dc, so the intermediate gear turns
    # 2 pi int rho'^(1/2) / int rho'^(3/2)
    # per sun turn: below a turn whenever rho' varies (its mean is 1). Independent quadrature on a fine grid:
    slope = train.relative_angle.evaluate(np.linspace(0, 2 * np.pi, 72000, endpoint=False), 1)
    expected = 2 * np.pi * np.sqrt(slope).mean() / (slope**1.5).mean()
    assert np.degrees(turn) == pytest.approx(np.degrees(expected), abs=1e-5)
    assert expected < 2 * np.pi and k_printed == pytest.approx(1 / (slope**1.5).mean(), rel=1e-9)


def test_published_table4_design(problem):
    """Wang et al. 2025 Table 4 against Table 1: P is reachable to 0.08 mm, the plate angle is off by 0.6 deg at P2,
    and the chain comes within sin^2(EBF) = 0.004 of jamming (closes, but below a 0.01 margin)."""
    evaluation = evaluate_design(problem, load_design(ROOT / "examples/vegetable_planting_table4.toml"))
    assert 0.03 < evaluation.position_errors_mm[1:].max() < 0.15
    assert 0.3 < np.abs(evaluation.angle_errors_deg).max() < 1.0
    assert 0 < evaluation.candidate.min_margin < 0.01
    assert [d.split(":")[0] for d in evaluation.candidate.defects] == ["closure"]
    low, high = evaluation.candidate.ratio_range
    assert 0.74 < low < 0.79 and 1.38 < high < 1.44       # regression pin (0.77 to 1.41 when written)


def test_cli_json_fields(example_result_from_synthesize, example_result_drawings_copied, tmp_path, capsys):
    code = main(["fivebar", str(EXAMPLE), "--json", "--no-animation", "--no-step", "--out", str(tmp_path)])
    report = json.loads(capsys.readouterr().out)
    assert code == 0
    for key in ("key_pose_position_errors_mm", "key_pose_angle_errors_deg", "min_discriminant",
                "relative_angle_monotonic", "design", "gear_closure_errors", "roundtrip_max_error_mm", "timings_s"):
        assert key in report
    assert len(report["key_pose_position_errors_mm"]) == 4 and report["relative_angle_monotonic"] is True
    assert {"region.png", "relative_angle.png", "gears.png", "trajectory.png", "report.md"} <= {
        p.name for p in tmp_path.iterdir()}


def _edited(**changes):
    data = read_toml(EXAMPLE)
    for path, value in changes.items():
        table, key = path.split("__")
        data[table][key] = value
    return data


@pytest.mark.parametrize("changes, words", [
    ({"ranges__ep": [100, 50]}, "ranges.ep"),
    ({"ranges__ep": [-55.0, 100.0]}, "ranges.ep = [-55.0, 100.0]: expected a length range (mm) that starts above zero"),
    ({"ranges__fp": [-1.0, 100.0]}, "ranges.fp = [-1.0, 100.0]: expected a length range (mm) that starts at or above"),
    ({"conditions__min_closure_margin": 1.5}, "conditions.min_closure_margin"),
    ({"conditions__ratio": [0.0, 2.0]}, "conditions.ratio"),
    ({"spline__control_points": 4}, "spline.control_points"),
])
def test_bad_fivebar_fields_are_named(changes, words):
    with pytest.raises(ProblemError, match=re.escape(words)):
        parse_problem(_edited(**changes), "f.toml")


def test_key_pose_count_and_turns_are_checked():
    data = read_toml(EXAMPLE)
    data["key_poses"] = data["key_poses"][:3]
    with pytest.raises(ProblemError, match="exactly 4 key poses"):
        parse_problem(data, "f.toml")
    data = read_toml(EXAMPLE)
    data["key_poses"][2]["carrier_turn_deg"] = 10.0
    with pytest.raises(ProblemError, match="strictly increasing"):
        parse_problem(data, "f.toml")


def test_ranges_that_empty_the_region_are_named():
    # 210 is a regression pin (the traced B-E dyads within the other ranges); the tracing is checked against the
    # exact curves in tests/fivebar/test_solution_region.py
    problem = parse_problem(_edited(ranges__x_e=[100.0, 200.0]), "f.toml")
    with pytest.raises(InfeasibleError,
                       match=r"no 2R chain B-E survives: ranges\.x_e removes the last 210 .*closest: B"):
        synthesize(problem)


def test_cli_exit_2_on_bad_design(tmp_path, capsys):
    bad = tmp_path / "design.toml"
    text = (ROOT / "examples/vegetable_planting_table4.toml").read_text()
    bad.write_text(text.replace("carrier_length_OA = 47.47", "carrier_length_OA = -1"))
    assert main(["fivebar", str(EXAMPLE), "--design", str(bad)]) == 2
    assert "design.carrier_length_OA" in capsys.readouterr().err


def test_region_without_a_feasible_five_bar_lists_counts_and_closest():
    # 1560 is a regression pin; tests/fivebar/test_solution_region.py checks the same pairs against the one-at-a-time
    # reference (fivebar.reference_region)
    problem = parse_problem(_edited(conditions__ratio=[0.95, 1.05]), "f.toml")
    with pytest.raises(InfeasibleError, match=r"none of the 1560 five-bars .*ratio: \d+.*closest: \[B"):
        synthesize(problem)


def test_design_whose_plates_cannot_reach_p1_is_refused(tmp_path, capsys):
    text = (ROOT / "examples/vegetable_planting_table4.toml").read_text()
    bad = tmp_path / "design.toml"
    bad.write_text(text.replace("push_plate_EP = 55.01", "push_plate_EP = 5.0"))
    assert main(["fivebar", str(EXAMPLE), "--design", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "design.push_plate_EP = 5.0" in err and "cannot be spanned" in err and "Traceback" not in err


def test_an_emptied_family_says_why_dyads_inside_every_range_were_dropped(problem):
    order = "order (relative angle not increasing through the key poses)"
    family = ChainFamily(synthesis=None, fixed=np.zeros((2, 2)), moving=np.ones((2, 2)), kept=np.zeros(2, bool),
                         reasons={"ranges.fp": 0, order: 2}, shortfalls={"fp": np.zeros(2)},
                         measures={"fp": np.full(2, 60.0)})
    with pytest.raises(InfeasibleError, match=r"F \(1\.0, 1\.0\) within the ranges, dropped by order") as error:
        _empty_family(problem, "3R chain O-A-F", family)
    assert "outside by" not in str(error.value)
    assert str(error.value).endswith(f"what would work: the closest lie within the ranges; {order} drops them: move "
                                     "the key poses")


def test_a_region_radius_that_traces_no_dyad_is_named():
    problem = parse_problem(_edited(region__radius_mm=1e-9), "f.toml")
    with pytest.raises(InfeasibleError, match=r"no 2R chain B-E traced: .*region\.radius_mm = 1e-09 mm"):
        synthesize(problem)

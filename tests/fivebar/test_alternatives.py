"""Every feasible candidate refined, judged on its own, merged, ranked, and the one ``--pick`` names built.

The module's problem is the vegetable planting example with wider ranges (|EP| to 125 mm, |FP| from
10 mm, x of E up to 100 mm) and coarse sampling: its 9 feasible candidates lie on both B-E-F
assembly branches and refine into two different mechanisms, one of them on the margin floor.
"""
import json
from dataclasses import replace

import numpy as np
import pytest

from tests.api.test_python_api import EXAMPLES, check_figures
from transplanter import side_process
from transplanter.cli import main
from transplanter.errors import ProblemError, SolverError
from transplanter.fivebar import alternatives
from transplanter.fivebar.alternatives import (
    ANGLE_TIE,
    MERGE_TOLERANCE,
    Failure,
    active_bounds,
    assess,
    merge,
    rank,
    reach,
    refine_all,
)
from transplanter.fivebar.design_solver import DesignSolver, HollowError
from transplanter.fivebar.figures import draw_figures
from transplanter.fivebar.nlp import CONCAVITY_LIMIT
from transplanter.fivebar.problem import parse_problem
from transplanter.fivebar.report import alternative_json
from transplanter.fivebar.synthesis import pick_alternative, synthesize
from transplanter.fivebar.whole_turn import CURVES
from transplanter.solve import ActiveBound as SolvedBound
from transplanter.toml_fields import read_toml

TURNS = np.linspace(0, 2 * np.pi, 3600, endpoint=False)


def wide_problem(samples: int = 300):
    data = read_toml(EXAMPLES / "vegetable_planting.toml")
    data["region"]["samples"] = samples
    data["ranges"].update(ep=[55.0, 125.0], fp=[10.0, 100.0], x_e=[-100.0, 100.0])
    return parse_problem(data, "wide.toml")


@pytest.fixture(scope="module")
def run():
    """The wide problem synthesised with alternative 2 picked, and the progress calls it made (~4 s); without the
    tolerance analysis, which no test here reads."""
    calls = []
    result = synthesize(wide_problem(), pick=2, progress=lambda step, done, total: calls.append((step, done, total)),
                        tolerance=False)
    return result, calls


def test_every_feasible_candidate_is_refined_or_failed_with_a_reason(run):
    result, calls = run
    feasible = len(result.region.feasible)
    starts = [k for alternative in result.alternatives for k in alternative.starts]
    failed = [failure.start for failure in result.failed]
    assert sorted(starts + failed) == list(range(feasible))
    assert all(failure.reason for failure in result.failed)
    assert 2 <= len(result.alternatives) < feasible        # merged: one mechanism from several starts
    assert [c for c in calls if c[0] == "refinement"] == [("refinement", k, feasible) for k in range(feasible + 1)]


def test_designs_reached_from_different_starts_are_merged_and_different_ones_kept(run):
    result, _ = run
    size = reach(result.problem)
    first, second = result.alternatives
    again = replace(first, starts=(99,))
    assert [a.starts for a in merge([first, second, again], size)] == [first.starts + (99,), second.starts]
    mech = first.design.mech
    for step, count in ((2 * MERGE_TOLERANCE * size, 2), (0.5 * MERGE_TOLERANCE * size, 1)):
        moved = replace(first, design=replace(first.design, mech=replace(mech, rod_length=mech.rod_length + step)))
        assert len(merge([first, moved], size)) == count


def test_alternatives_are_ranked_by_the_documented_rule(run):
    """Constructed alternatives with known angles, misses and ratio spreads come out in the order the rule gives:
    the largest smallest transmission angle at E first; near-equal angles by the smaller miss, equal misses by the
    gentler ratio;
    an angle just outside the tie tolerance is not a tie even with the smallest miss."""
    result, _ = run
    base = result.alternatives[0]
    table = {"C": (40.0, 5.0, 5.0), "A": (30.0, 0.5, 2.0), "B": (30.01, 0.1, 3.0), "D": (30.005, 0.1, 1.5),
             "F": (29.9, 0.0, 1.0), "E": (10.0, 0.0, 1.0)}
    made = {name: replace(base, transmission_angle=np.radians(angle), return_misses_mm=np.array([miss, miss / 2]),
                          ratio_range=(0.5, 0.5 * spread), starts=(k,))
            for k, (name, (angle, miss, spread)) in enumerate(table.items())}
    names = {alternative.starts: name for name, alternative in made.items()}
    ordered = rank(list(made.values()), reach(result.problem))
    assert [names[a.starts] for a in ordered] == ["C", "D", "B", "A", "F", "E"]
    assert (30.01 - 30.0) < ANGLE_TIE * 30.01 < (30.01 - 29.9)

    angles = [a.transmission_angle for a in result.alternatives]
    assert angles[0] > angles[1] * (1 + ANGLE_TIE)           # no tie in the module's problem: angle decides


def test_pick_2_builds_the_second_alternative(run):
    result, _ = run
    report = result.to_json()
    second = result.alternatives[1]
    assert result.design is second.design and report["picked"] == 2
    assert report["design"] == alternative_json(second, 2, result.problem.poses[0])["design"]
    assert report["design"] != alternative_json(result.alternatives[0], 1, result.problem.poses[0])["design"]
    assert result.start is result.region.feasible[second.starts[0]]
    size = reach(result.problem)
    assert max(report["key_pose_position_errors_mm"]) < 1e-9 * size       # gears built for this design
    assert report["transmission_angle_min_deg"] == pytest.approx(np.degrees(second.transmission_angle), abs=1e-12)
    assert report["active_bounds"] == alternative_json(second, 2, result.problem.poses[0])["active_bounds"]
    json.dumps(report, allow_nan=False)
    text = result.to_markdown()
    table = text[text.index("## Alternatives"):text.index("## Solution region")]
    assert "| 2 (built) |" in table and "| 1 |" in table and "min EBF (deg)" in table and "min at E (deg)" in table


def test_a_pick_beyond_the_alternatives_is_refused_naming_the_range(run, tmp_path, capsys):
    result, _ = run
    with pytest.raises(ProblemError, match=r"^--pick = 3: expected 1 to 2 \(wide\.toml gives 2 alternatives\)$"):
        pick_alternative(list(result.alternatives), 3, "wide.toml")
    with pytest.raises(ProblemError, match=r"--pick = 0: expected a whole number of at least 1"):
        synthesize(result.problem, pick=0)
    example = (EXAMPLES / "vegetable_planting.toml").read_text().replace("samples = 2000", "samples = 500")
    path = tmp_path / "coarse.toml"
    path.write_text(example)                       # one feasible candidate: one alternative
    assert main(["fivebar", str(path), "--pick", "2"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--pick = 2: expected 1 (" in err and "Traceback" not in err


def test_transmission_angles_match_the_hinge_positions(run):
    """The transmission angle between EF and BE at E, and the closure angle EBF between BE and BF, from the
    forward kinematics' hinges by arccos, folded to [0, 90] deg: their minima and where they occur, and asin of
    eq 10's margin for EBF."""
    result, _ = run
    for alternative in result.alternatives:
        mech, relative = alternative.design.mech, alternative.design.relative_angle
        state = mech.forward(TURNS, relative.evaluate(TURNS))
        e, f, b = state["e"], state["f"], mech.hinge_b

        def folded(u, v):
            angle = np.arccos(np.sum(u * v, axis=1) / np.linalg.norm(u, axis=1) / np.linalg.norm(v, axis=1))
            return np.minimum(angle, np.pi - angle)

        at_b, at_e = folded(e - b, f - b), folded(f - e, b - e)
        assert alternative.transmission_angle == pytest.approx(at_e.min(), abs=1e-9)
        assert alternative.transmission_turn == TURNS[at_e.argmin()]
        assert alternative.closure_angle == pytest.approx(at_b.min(), abs=1e-9)
        assert alternative.closure_turn == TURNS[at_b.argmin()]
        assert alternative.closure_angle == pytest.approx(np.arcsin(np.sqrt(state["margin"].min())), abs=1e-9)
    report = result.to_json()
    assert report["transmission_angle_min_deg"] == pytest.approx(np.degrees(result.alternatives[1].transmission_angle))


def test_the_bounds_the_nlp_sits_on_are_reported_with_the_problems_limits_and_the_designs_own_values(run):
    """The NLP decides which bounds bind (``solve.active``); the report gives each with the problem's limit
    and the value of the design's own evaluation, in the order ranges, margin, ratio, return tolerance
    (with its points), a kappa; with a tolerance of 0 every return point is on it."""
    result, _ = run
    problem = result.problem
    alternative = result.alternatives[0]
    design = alternative.design
    margin, ratios, misses = alternative.min_closure_margin, alternative.ratio_range, alternative.return_misses_mm
    tightest = int(np.argmin(design.min_curvature))
    nlp_says = (SolvedBound(f"a kappa of the {CURVES[tightest]} pitch curve", "lower", -6.0, -6.0, "curvature", (3,)),
                SolvedBound("ratio", "lower", 4.0, 4.0, "slope", (7,)),
                SolvedBound("conditions.return_tolerance_mm", "upper", 0.01, 0.01, "return_misses", (0, 2)),
                SolvedBound("ranges.ep", "upper", 1.0, 1.0, "ranges.ep", (0,)),
                SolvedBound("min_closure_margin", "lower", 0.01, 0.01, "quality", (0,)))
    held = replace(design, active_bounds=nlp_says)
    reported = active_bounds(problem, held, margin, ratios, misses)
    assert [(b.name, b.side) for b in reported] == [
        ("ranges.ep", "upper"), ("min_closure_margin", "lower"), ("ratio", "lower"),
        ("conditions.return_tolerance_mm (return points 1, 3)", "upper"),
        (f"a kappa of the {CURVES[tightest]} pitch curve", "lower")]
    assert [b.limit for b in reported] == [problem.ranges["ep"][1], problem.min_closure_margin, problem.ratio_bounds[0],
                                           problem.return_tolerance_mm, design.curvature_floor]
    assert [b.value for b in reported] == [pytest.approx(design.mech.ep, abs=1e-12), margin, ratios[0],
                                           max(misses[0], misses[2]), design.min_curvature[tightest]]
    none_held = replace(design, active_bounds=())
    assert active_bounds(problem, none_held, margin, ratios, misses) == ()
    exact = active_bounds(replace(problem, return_tolerance_mm=0.0), none_held, margin, ratios, misses)
    assert [b.name for b in exact] == [f"conditions.return_tolerance_mm (return points "
                                       f"{', '.join(str(j + 1) for j in range(len(misses)))})"]


def test_a_refined_design_that_breaks_a_condition_fails_with_the_reason(run):
    result, _ = run
    problem, alternative = result.problem, result.alternatives[1]
    margin = alternative.min_closure_margin
    floor = (1 + margin) / 2            # above the design's margin, below 1
    failure = assess(replace(problem, min_closure_margin=floor), alternative.design, 4)
    assert isinstance(failure, Failure) and failure.start == 4
    assert failure.reason.startswith(f"closure: min sin^2(EBF) = {margin:.4f} < {floor:g}")
    ep = float(alternative.design.mech.ep)
    failure = assess(replace(problem, ranges={"ep": (55.0, ep - 1.0)}), alternative.design, 0)
    assert "ranges.ep" in failure.reason

    class Solver:
        """Refines by the module's designs, but the NLP fails from the second candidate."""

        def refine(self, candidate):
            if candidate is result.region.feasible[1]:
                raise SolverError("no", "Maximum_Iterations_Exceeded")
            return result.alternatives[0].design

        def make_convex(self, candidate, design):
            return design

        def restroke(self, candidate, design, point, turn):
            raise SolverError("no", "Maximum_Iterations_Exceeded")

    found, failed, seconds = refine_all(problem, Solver(), result.region.feasible[:3])
    assert [a.starts for a in found] == [(0, 2)] and len(seconds) == 3
    assert failed == [Failure(1, "the design NLP did not converge: Maximum_Iterations_Exceeded")]


def test_figures_name_hinges_gears_and_show_the_trade_off(run):
    result, _ = run
    figures = draw_figures(result)
    check_figures({"tradeoff": figures["tradeoff"]}, {"tradeoff"})
    ax = figures["tradeoff"].axes[0]
    assert "(deg)" in ax.get_xlabel() and "(mm)" in ax.get_ylabel()
    assert {text.get_text() for text in ax.texts} == {str(k) for k in range(1, len(result.alternatives) + 1)}
    picked = [line for line in ax.get_lines() if line.get_label().startswith("picked")][0]
    second = result.alternatives[1]
    assert picked.get_xdata()[0] == pytest.approx(np.degrees(second.transmission_angle))
    assert picked.get_ydata()[0] == pytest.approx(second.largest_miss_mm)
    feasible = len(result.region.feasible)
    assert f"refined from {feasible - len(result.failed)} of {feasible} region candidates" in ax.get_title()
    one_failed = replace(result, failed=(Failure(0, "a reason"),))
    assert "(1 failed: see the report)" in draw_figures(one_failed)["tradeoff"].axes[0].get_title()
    assert {"O", "A", "B", "E", "F", "P"} <= {text.get_text() for text in figures["trajectory"].axes[0].texts}
    gear_labels = [text.get_text() for text in figures["gears"].axes[1].get_legend().get_texts()]
    one, two = result.toothed.counts
    assert gear_labels == [f"sun (driver, stage 1), {one} teeth", f"first intermediate (driven, stage 1), {one} teeth",
                           f"second intermediate (driver, stage 2), {two} teeth",
                           f"planet (driven, stage 2), {two} teeth"]


def test_a_start_whose_curves_cannot_be_held_to_shaper_hollows_fails_with_the_unheld_numbers(run, monkeypatch):
    """When IPOPT fails with the curves held to a kappa >= -CONCAVITY_LIMIT, ``refine`` does not hand on a
    design with hollows no cutter makes: it raises, naming the status and the hold. Where every start failed,
    ``refine_all`` lists each such start with the least a kappa of each curve of the design made without the
    hold (here computed again, by its own solve); where a start gave a design, that re-solve is not made. Every
    solver here is a fresh twin of one built solver (``DesignSolver.twin``: the same state, no build of its own)."""
    result, _ = run
    problem, start = result.problem, result.region.feasible[0]
    monkeypatch.setattr(side_process, "FORKS", False)       # every solve in this process, where it is counted
    built = DesignSolver(problem)

    def fresh(kind: type[DesignSolver]) -> DesignSolver:
        solver = built.twin()
        solver.__class__ = kind
        return solver

    class HeldFails(DesignSolver):
        unheld_solves = 0

        def solve(self, start, added_turns=(), warm=None, curvature_floor=None, iteration_limit=None,
                  closure_in_quality=False, continues=False):
            if curvature_floor is not None:
                raise SolverError("held", "Infeasible_Problem_Detected")
            HeldFails.unheld_solves += 1
            return super().solve(start, added_turns, warm, curvature_floor, iteration_limit, closure_in_quality,
                                 continues)

    unheld = built.twin()._exchange(start, None)
    with pytest.raises(HollowError) as caught:
        fresh(HeldFails).refine(start)
    reason = caught.value.reason
    assert "Infeasible_Problem_Detected" in reason and f"{-CONCAVITY_LIMIT:g}" in reason
    assert HeldFails.unheld_solves == 0
    found, failed, _ = refine_all(problem, fresh(HeldFails), [start])
    assert found == [] and [(f.start, f.held) for f in failed] == [(0, True)]
    assert failed[0].reason.startswith(f"{reason}; without that hold: ")
    for curve, value in zip(CURVES, unheld.min_curvature, strict=True):
        assert f"{curve} {value:.3f}" in failed[0].reason
    assert HeldFails.unheld_solves > 0

    class SecondHeldFails(HeldFails):
        """The first start is refined as the module's design; the second fails with the hold."""

        def refine(self, candidate):
            if candidate is start:
                return result.alternatives[0].design
            return super().refine(candidate)

    HeldFails.unheld_solves = 0
    monkeypatch.setattr(alternatives, "DesignSolver", SecondHeldFails)     # lane 1's solver too
    found, failed, _ = refine_all(problem, fresh(SecondHeldFails), result.region.feasible[:2])
    assert len(found) == 1 and [(f.start, f.held, f.reason) for f in failed] == [(1, True, reason)]
    assert HeldFails.unheld_solves == 0

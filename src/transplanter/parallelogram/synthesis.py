"""The onion-transplanter jobs: design one (``synthesize``), evaluate a given design (``evaluate_design``)."""
from __future__ import annotations

import dataclasses
import time
from collections.abc import Callable
from typing import Any

import numpy as np

from transplanter.api_arguments import require_pick, require_problem, require_progress, require_switch
from transplanter.errors import ProblemError, SolverError, TransplanterError
from transplanter.gears.drawings import bore_failures
from transplanter.gears.result import GearResult
from transplanter.gears.synthesis import tooth_counts
from transplanter.parallelogram.evaluation import (
    EVALUATION_SAMPLES,
    DesignFile,
    Evaluation,
    evaluate,
    evaluate_published,
    problem_design,
)
from transplanter.parallelogram.gear_pair import gear_pair
from transplanter.parallelogram.kinematics import mechanisms
from transplanter.parallelogram.nlp import polish
from transplanter.parallelogram.problem import ParallelogramProblem
from transplanter.parallelogram.result import DesignReport, ParallelogramResult, Polished, objective_values
from transplanter.parallelogram.search import SearchResult, nsga2
from transplanter.parallelogram.trajectory import measure
from transplanter.tolerance import analyse
from transplanter.toml_fields import shown

#: Agreement asked of the independent evaluation with the search's values, relative to the problem's size.
AGREEMENT = 1e-6


def requirement_failures(problem: ParallelogramProblem, evaluation: Evaluation, gear: GearResult) -> tuple[str, ...]:
    """Why a design misses the problem's requirements (empty when it meets them): its depth on the fine
    grid within the depth band, its gear pair (gear library) convex and free of undercut, the gears' keyed bores
    clear of their teeth (``gears.drawings.bore_failures``)."""
    failures = []
    low, high = problem.depth_band
    if not low - AGREEMENT * high <= evaluation.depth <= high * (1 + AGREEMENT):
        failures.append(f"depth {evaluation.depth:.4f} mm outside the band [{low:g}, {high:g}] mm")
    if not all(gear.convex) or any(gear.undercut or ()):
        failures.append(f"gear pair: convex {gear.convex}, undercut {gear.undercut}")
    return (*failures, *bore_failures(gear))


def _checks(problem: ParallelogramProblem, search: SearchResult, rank: int, evaluation: Evaluation,
            gear: GearResult) -> tuple[str, ...]:
    """Why the chosen design fails (empty when it passes): the fine evaluation must agree with the search
    and the design meet the requirements (``requirement_failures``)."""
    failures = []
    high = problem.depth_band[1]
    if abs(evaluation.depth - search.depth[rank - 1]) > AGREEMENT * high:
        failures.append(f"depth {evaluation.depth:.6f} mm on the fine grid, "
                        f"{search.depth[rank - 1]:.6f} mm in the search")
    if abs(evaluation.vx_release - search.vx_release[rank - 1]) > AGREEMENT * problem.forward_speed:
        failures.append(f"Vx {evaluation.vx_release:.6f} mm/s on the fine grid, "
                        f"{search.vx_release[rank - 1]:.6f} in the search")
    return tuple(failures) + requirement_failures(problem, evaluation, gear)


def toothed_pair(problem: ParallelogramProblem, design: dict):
    """The gear library's pair for ``design`` scaled to the nearest whole tooth count at the module, with
    tooth outlines (the trajectory is unchanged: b/l is kept); the unscaled pair and the reason when the
    teeth cannot be cut."""
    pair = gear_pair(design, problem.module, problem.pressure_angle, problem.driver_speed, source=problem.source)
    teeth = tooth_counts(pair.design, problem.module).counts[0]
    try:
        return gear_pair(design, problem.module, problem.pressure_angle, problem.driver_speed, teeth,
                         problem.source), ()
    except TransplanterError as error:
        return pair, (f"gear teeth ({teeth} at module {problem.module:g}): {error}",)


def dominates(first: np.ndarray, second: np.ndarray, scale: np.ndarray) -> bool:
    """``first`` no worse than ``second`` in every objective and better in one (within 1e-9 of ``scale``)."""
    slack = 1e-9 * scale
    return bool(np.all(first <= second + slack) and np.any(first < second - slack))


def _polish(problem: ParallelogramProblem, chosen: dict, evaluation: Evaluation) -> Polished:
    """The NLP from the chosen design, its independent evaluation and whether it dominates the start."""
    measures = measure(mechanisms(problem, chosen), problem.depth_window, EVALUATION_SAMPLES)
    try:
        solution = polish(problem, chosen, measures)
    except SolverError as error:
        return Polished(None, None, False, str(error.status), 0, 0.0)
    result = evaluate(problem, solution.variables, "polished")
    scale = np.array([problem.forward_speed, problem.depth_target, problem.vertical_range_target])
    better = dominates(objective_values(problem, result), objective_values(problem, evaluation), scale)
    return Polished(solution.variables, result, better, solution.status, solution.iterations, solution.seconds)


def synthesize(problem: ParallelogramProblem, pick: int | None = None,
               progress: Callable[[str, int, int], None] | None = None, polish_nlp: bool = True,
               tolerance: bool = True, executor: Any = None) -> ParallelogramResult:
    """NSGA-II over the bounded variables, the design ranked ``pick`` (1, the knee, by default)
    evaluated again on a fine grid, polished by an NLP (Vx(t_E) = 0, H at its target, f3 minimised),
    the final design's gear pair from the gear library and, unless ``tolerance`` is False, how precise
    the built mechanism will be (``tolerance.analyse`` with the problem's ``[tolerances]``).
    ``executor`` (a ``concurrent.futures.Executor`` or a ``distributed.Client``): where NSGA-II scores its
    populations, in slices (``search.nsga2``); the search is the same as in this process.

    Raises
    ------
    ProblemError
        When [search.bounds] is empty or ``pick`` is beyond the Pareto designs.
    InfeasibleError
        When no design meets the depth band and the gear constraints (with the closest design).
    """
    require_problem(problem, ParallelogramProblem, "parallelogram")
    rank = require_pick(pick)
    require_progress(progress)
    require_switch("polish_nlp", polish_nlp)
    require_switch("tolerance", tolerance)
    if not problem.bounds:
        raise ProblemError(f"{problem.source}: search.bounds is missing: expected [low, high] for at least one of "
                           "m11, b, l, l1, alpha_deg")
    timings = {}
    start = time.perf_counter()
    search = nsga2(problem, progress, executor=executor)
    timings["nsga2"] = time.perf_counter() - start
    if rank > len(search.designs):
        raise ProblemError(f"{problem.source}: --pick {pick}: expected a rank from 1 to {len(search.designs)} "
                           "(the Pareto designs, 1 = the knee)")
    chosen = {**problem.design, **search.variables(rank)}
    start = time.perf_counter()
    evaluation = evaluate(problem, chosen, "chosen")
    reference = evaluate(problem, problem.design, "start")
    published = evaluate_published(problem, problem_design(problem))
    timings["evaluation"] = time.perf_counter() - start
    polished = None
    if polish_nlp:
        start = time.perf_counter()
        polished = _polish(problem, chosen, evaluation)
        timings["nlp_polish"] = time.perf_counter() - start
    final = polished.variables if polished is not None and polished.variables is not None else chosen
    start = time.perf_counter()
    gear, gear_failures = toothed_pair(problem, final)
    timings["gear"] = time.perf_counter() - start
    failures = _checks(problem, search, rank, evaluation, gear) + gear_failures
    if polished is not None:
        failures += polished.failures(problem)
    result = ParallelogramResult(problem, search, rank, chosen, evaluation, gear, reference, timings, failures,
                                 polished, published)
    return _analysed(result, timings) if tolerance else result


def _analysed(result: ParallelogramResult | DesignReport, timings: dict):
    """``result`` with its tolerance analysis (``tolerance.analyse`` with the problem's ``[tolerances]``), its
    time in ``timings`` (the result's own)."""
    start = time.perf_counter()
    analysis = analyse(result, result.problem.tolerances)
    timings["tolerance"] = time.perf_counter() - start
    return dataclasses.replace(result, tolerance=analysis)


def evaluate_design(problem: ParallelogramProblem, given: DesignFile, tolerance: bool = True) -> DesignReport:
    """A given design under every reading of its gear (as printed, closed) and of the conventions
    (the file's, eq 17 literal), with its closed gear pair from the gear library. It fails when the
    closed curve under the file's conventions misses the problem's requirements
    (``requirement_failures``); the other readings are reported, not checked.

    Parameters
    ----------
    problem : ParallelogramProblem
        Machine, conventions and objectives (its own [design] is not used).
    given : DesignFile
        The eight variables, and optionally the printed gear values and published figures.
    tolerance : bool, optional
        Analyse how precise the built design will be (``tolerance.analyse`` with the problem's
        ``[tolerances]``; default True).
    """
    require_problem(problem, ParallelogramProblem, "parallelogram")
    if not isinstance(given, DesignFile):
        raise ProblemError(f"given = {shown(given)!r}: expected a DesignFile (from "
                           "transplanter.parallelogram.load_design(path))")
    start = time.perf_counter()
    rows = evaluate_published(problem, given)
    closed = evaluate(problem, given.design)
    timings = {"evaluation": time.perf_counter() - start}
    start = time.perf_counter()
    gear = gear_pair(given.design, problem.module, problem.pressure_angle, problem.driver_speed,
                     source=given.source)
    timings["gear"] = time.perf_counter() - start
    report = DesignReport(problem, given, rows, closed, gear, timings, requirement_failures(problem, closed, gear))
    return _analysed(report, timings) if tolerance else report

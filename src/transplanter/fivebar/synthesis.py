"""The main job: from a five-bar problem to a verified mechanism with its gear train.

Region (``fivebar.region``) -> every feasible candidate refined by the design NLP (one solver
per problem), judged, merged and ranked (``fivebar.alternatives``) -> the picked alternative's
gear train with whole teeth, cut and mesh-checked (``trains.toothed_train``) -> independent
verification (``fivebar.verification``) -> with ``[support]``, the seedling support timed to it
(``fivebar.support``).
When the region is empty, the error names the condition that emptied it and the closest
candidates.
"""
from __future__ import annotations

import dataclasses
import time
from typing import Any

import numpy as np

from transplanter.api_arguments import require_pick, require_progress, require_switch
from transplanter.errors import InfeasibleError, ProblemError, SolverError
from transplanter.fivebar.alternatives import Alternative, Progress, refine_all, with_gear_sizes
from transplanter.fivebar.band_search import band_starts
from transplanter.fivebar.design_solver import DesignSolver
from transplanter.fivebar.kinetostatics import kinetostatics
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import ChainFamily, Region
from transplanter.fivebar.relaxation import relaxation_hint
from transplanter.fivebar.result import FiveBarResult
from transplanter.fivebar.support import design_support
from transplanter.fivebar.verification import verify
from transplanter.fivebar.whole_turn import fine_turns
from transplanter.tolerance import analyse
from transplanter.trains.pressure_angle import stage_pressure_angles
from transplanter.trains.toothed_train import design_toothed_train


def _empty_family(problem: FiveBarProblem, name: str, family: ChainFamily):
    if len(family.fixed) == 0:
        raise InfeasibleError(f"{problem.source}: no {name} traced: no dyad of the key poses has its hinges within "
                              f"region.radius_mm = {problem.radius_mm:g} mm of the poses' centroid; enlarge it")
    stage = [key for key, count in family.reasons.items() if count][-1]      # the one that left none
    hinges = "B, E" if name.endswith("B-E") else "A, F"
    total = sum(family.shortfalls.values())
    closest = np.argsort(total)[:3]
    other = [key for key in family.reasons if not key.startswith("ranges.")]

    def miss(k: int) -> str:
        outside = [f"{key} {value[k]:.1f}" for key, value in family.shortfalls.items() if value[k] > 0]
        return "outside by " + ", ".join(outside) if outside else "within the ranges, dropped by " + " / ".join(other)

    listed = "; ".join(f"{hinges.split(', ')[0]} ({family.fixed[k][0]:.1f}, {family.fixed[k][1]:.1f}) "
                       f"{hinges.split(', ')[1]} ({family.moving[k][0]:.1f}, {family.moving[k][1]:.1f}) {miss(k)}"
                       for k in closest)
    raise InfeasibleError(
        f"{problem.source}: no {name} survives: {stage} removes the last {family.reasons[stage]} of "
        f"{len(family.fixed)} traced dyads ({', '.join(f'{k}: {v}' for k, v in family.reasons.items())}); "
        f"closest: {listed}; {_what_would_keep(problem, family, closest[0], other)}")


def _what_would_keep(problem: FiveBarProblem, family: ChainFamily, k: int, other: list[str]) -> str:
    """The ranges, widened just enough (to 0.1 mm outward), that keep dyad ``k`` of an emptied family; or, when it
    lies within them, the other conditions that drop it."""
    widened = []
    for key, values in family.measures.items():
        low, high = problem.ranges.get(key, (-np.inf, np.inf))
        if family.shortfalls[key][k] > 0:
            value = values[k]
            widened.append(f"ranges.{key} = [{min(low, np.floor(value * 10) / 10):g}, "
                           f"{max(high, np.ceil(value * 10) / 10):g}]")
    if widened:
        return "what would work: " + " and ".join(widened) + " keeps the closest"
    return f"what would work: the closest lie within the ranges; {' / '.join(other)} drops them: move the key poses"


def _no_feasible_pair(problem: FiveBarProblem, region: Region):
    counts = ", ".join(f"{k}: {v}" for k, v in sorted(region.pair_defects.items(), key=lambda kv: -kv[1]))
    closest = sorted(region.candidates, key=lambda c: len(c.defects))[:3]
    lines = "; ".join(f"[B ({c.mech.hinge_b[0]:.1f}, {c.mech.hinge_b[1]:.1f}), OA {c.mech.carrier_length:.1f}: "
                      f"{' / '.join(c.defects)}]" for c in closest)
    raise InfeasibleError(f"{problem.source}: none of the {len(region.candidates)} five-bars of the region is "
                          f"feasible (first failing condition per pair: {counts}); closest: {lines}; "
                          f"{relaxation_hint(problem, region)}")


def pick_alternative(alternatives: list[Alternative], pick: int, source: str) -> Alternative:
    """Alternative number ``pick`` (1-based, in ranked order); a ``ProblemError`` naming the valid range
    when there is no such alternative."""
    if pick > len(alternatives):
        count = len(alternatives)
        valid = "1" if count == 1 else f"1 to {count}"
        raise ProblemError(f"--pick = {pick}: expected {valid} ({source} gives {count} "
                           f"alternative{'s' if count > 1 else ''})")
    return alternatives[pick - 1]


def synthesize(problem: FiveBarProblem, pick: int | None = None, progress: Progress | None = None,
               tolerance: bool = True, executor: Any = None) -> FiveBarResult:
    """Design the five-bar and its four-gear planetary train for ``problem``, and verify it.

    Every feasible region candidate is refined by the design NLP; the results are judged by
    their own forward evaluation, merged where they are one mechanism, and ranked
    (``fivebar.alternatives``: the largest smallest transmission angle at E first). Alternative
    ``pick`` gets its gears and the verification.

    Parameters
    ----------
    problem : FiveBarProblem
        Key poses, return points, ranges and conditions (from ``load_problem`` or
        ``parse_problem``; mm and radians inside).
    pick : int, optional
        Which alternative to build, 1-based in ranked order (default 1, the best).
    progress : callable, optional
        ``progress(step, done, total)``, called with done = 0 when a step starts and after each
        unit of it; steps ``"region"``, ``"refinement"`` (one unit per candidate), ``"gears"``,
        ``"verification"``, ``"support"`` (with ``[support]``), ``"loads"``, ``"tolerance"``.
    tolerance : bool, optional
        Analyse how precise the built mechanism will be (``tolerance.analyse`` with the problem's
        ``[tolerances]``; default True).
    executor : concurrent.futures.Executor or distributed.Client, optional
        Where the regions of pose sets drawn inside the key poses' bands are built, several at once
        (``band_search``); the result is the one built here.

    Returns
    -------
    FiveBarResult
        The region, the ranked alternatives and failed candidates, the picked design with its
        start candidate, gear train and forward verification; ``to_json()`` gives the report.

    Raises
    ------
    ProblemError
        ``pick`` is not a whole number from 1 to the number of alternatives.
    InfeasibleError
        The region holds no feasible five-bar: the message names the condition and the
        closest candidates.
    SolverError
        No refinement succeeded (the reason for each candidate is given).
    """
    pick = require_pick(pick)
    require_progress(progress)
    require_switch("tolerance", tolerance)
    timings: dict[str, object] = {}
    start = _step(progress, "region")
    starts = band_starts(problem, executor)
    region = starts.region
    timings["region"] = _done(progress, "region", start)
    if not region.feasible and len(starts.trials) > 1:
        raise InfeasibleError(f"{problem.source}: no pose set inside the key poses' bands gives a feasible five-bar: "
                              f"{len(starts.trials)} tried (the bands' centres, then region.band_samples = "
                              f"{problem.band_samples} drawn sets); the condition that binds most often: "
                              f"{starts.most_binding()}; relax that condition, widen the bands or draw more sets "
                              "(region.band_samples)")
    if not region.receiving.kept.any():
        _empty_family(starts.problem, "2R chain B-E", region.receiving)
    if not region.carrier.kept.any():
        _empty_family(starts.problem, "3R chain O-A-F", region.carrier)
    if not region.feasible:
        _no_feasible_pair(starts.problem, region)

    start = time.perf_counter()
    solver = DesignSolver(problem)
    timings["nlp_build"] = time.perf_counter() - start
    start = time.perf_counter()
    alternatives, failed, seconds = refine_all(problem, solver, region.feasible, progress)
    timings["nlp"] = time.perf_counter() - start
    timings["nlp_per_candidate"] = seconds
    if not alternatives:
        raise SolverError(f"{problem.source}: none of the {len(failed)} feasible region candidates refined into a "
                          f"design that passes its checks (each one's reason names the condition that held it: "
                          "relax that condition or the ranges)",
                          "; ".join(f"{f.start + 1}: {f.reason}" for f in failed))
    alternatives = [with_gear_sizes(problem, alternative) for alternative in alternatives]
    chosen = pick_alternative(alternatives, pick, problem.source)
    design = chosen.design

    given, problem = problem, problem.with_poses(design.poses, design.carrier_turns)  # the key poses the design meets
    start = _step(progress, "gears")
    toothed = design_toothed_train(design.relative_angle, float(design.mech.carrier_length), problem.gearing,
                                   problem.source)
    timings["gears"] = _done(progress, "gears", start)
    timings.update((f"gears_{step}", seconds) for step, seconds in toothed.timings_s.items())
    start = _step(progress, "verification")
    verification = verify(problem, design.mech, design.relative_angle, toothed.train, design.stroke.carrier_turns)
    timings["verification"] = _done(progress, "verification", start)
    support = None
    if problem.support is not None:
        start = _step(progress, "support")
        support = design_support(problem.support, design.mech, design.relative_angle, problem.carrier_turns,
                                 design.stroke.carrier_turns, problem.source)
        timings["support"] = _done(progress, "support", start)
    start = _step(progress, "loads")
    pressure = stage_pressure_angles(design.relative_angle, toothed.train.correction, problem.gearing, fine_turns())
    loads = kinetostatics(design.mech, design.relative_angle, problem.carrier_turns, problem.load)
    timings["loads"] = _done(progress, "loads", start)
    result = FiveBarResult(problem, region, region.feasible[chosen.starts[0]], design, toothed, verification, timings,
                           tuple(alternatives), tuple(failed), pick, pressure, loads, given.pose_bands, starts.trials,
                           support)
    if not tolerance:
        return result
    start = _step(progress, "tolerance")
    analysis = analyse(result, problem.tolerances)
    timings["tolerance"] = _done(progress, "tolerance", start)
    return dataclasses.replace(result, tolerance=analysis)


def _step(progress: Progress | None, step: str) -> float:
    """Say that a one-unit ``step`` starts; its start time."""
    if progress:
        progress(step, 0, 1)
    return time.perf_counter()


def _done(progress: Progress | None, step: str, start: float) -> float:
    """Say that a one-unit ``step`` is done; its wall time (s)."""
    if progress:
        progress(step, 1, 1)
    return time.perf_counter() - start

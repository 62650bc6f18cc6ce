"""The main job: from a five-bar problem to a verified mechanism with its gear train.

Region (``fivebar.region``) -> best feasible candidate -> design NLP (``fivebar.nlp``, one
solver per problem) -> gear train (``trains.planetary``) -> independent verification
(``fivebar.verification``).
When the region is empty, the error names the condition that emptied it and the closest
candidates.
"""
from __future__ import annotations

import time

import numpy as np

from transplanter.errors import InfeasibleError, ProblemError, SolverError
from transplanter.fivebar.nlp import DesignSolver
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import ChainFamily, Region, solution_region
from transplanter.fivebar.result import FiveBarResult
from transplanter.fivebar.verification import verify
from transplanter.trains.planetary import design_train

#: Region candidates the NLP is started from, best first, before giving up.
STARTS = 3


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
        f"closest: {listed}")


def _no_feasible_pair(problem: FiveBarProblem, region: Region):
    counts = ", ".join(f"{k}: {v}" for k, v in sorted(region.pair_defects.items(), key=lambda kv: -kv[1]))
    closest = sorted(region.candidates, key=lambda c: len(c.defects))[:3]
    lines = "; ".join(f"[B ({c.mech.hinge_b[0]:.1f}, {c.mech.hinge_b[1]:.1f}), OA {c.mech.carrier_length:.1f}: "
                      f"{' / '.join(c.defects)}]" for c in closest)
    raise InfeasibleError(f"{problem.source}: none of the {len(region.candidates)} five-bars of the region is "
                          f"feasible (first failing condition per pair: {counts}); closest: {lines}")


def center_distances(problem: FiveBarProblem, carrier_length: float) -> tuple[float, float]:
    if problem.center_distances is None:
        return carrier_length / 2, carrier_length / 2
    a1, a2 = problem.center_distances
    if a1 + a2 < carrier_length or abs(a1 - a2) > carrier_length:
        raise ProblemError(f"{problem.source}: gears = [{a1:g}, {a2:g}] mm: expected center distances that can span "
                           f"the carrier O-A = {carrier_length:.3f} mm (a1 + a2 >= OA >= |a1 - a2|)")
    return a1, a2


def synthesize(problem: FiveBarProblem) -> FiveBarResult:
    """Design the five-bar and its four-gear planetary train for ``problem``, and verify it.

    Parameters
    ----------
    problem : FiveBarProblem
        Key poses, return points, ranges and conditions (from ``load_problem`` or
        ``parse_problem``; mm and radians inside).

    Returns
    -------
    FiveBarResult
        The region, the start candidate, the NLP design, the gear train and the forward
        verification; ``to_json()`` gives the report.

    Raises
    ------
    InfeasibleError
        The region holds no feasible five-bar: the message names the condition and the
        closest candidates.
    SolverError
        IPOPT failed from each of the ``STARTS`` best candidates (the statuses are given).
    """
    timings = {}
    start = time.perf_counter()
    region = solution_region(problem)
    timings["region"] = time.perf_counter() - start
    if not region.receiving.kept.any():
        _empty_family(problem, "2R chain B-E", region.receiving)
    if not region.carrier.kept.any():
        _empty_family(problem, "3R chain O-A-F", region.carrier)
    if not region.feasible:
        _no_feasible_pair(problem, region)

    start = time.perf_counter()
    solver = DesignSolver(problem)
    timings["nlp_build"] = time.perf_counter() - start
    start = time.perf_counter()
    failures = []
    for candidate in region.feasible[:STARTS]:
        try:
            design = solver.refine(candidate)
            break
        except SolverError as error:
            failures.append(error.status)
    else:
        raise SolverError(f"{problem.source}: the design NLP failed from the {len(failures)} best region candidates",
                          ", ".join(failures))
    timings["nlp"] = time.perf_counter() - start

    start = time.perf_counter()
    train = design_train(design.relative_angle, center_distances(problem, design.mech.carrier_length), problem.source)
    timings["gears"] = time.perf_counter() - start
    start = time.perf_counter()
    verification = verify(problem, design.mech, design.relative_angle, train, design.stroke.carrier_turns)
    timings["verification"] = time.perf_counter() - start
    return FiveBarResult(problem, region, candidate, design, train, verification, timings)

"""Solution region of the five-bar (Wang et al. 2025 section 3.2.1, Figure 5).

The 2R chain B-E is a 4-pose Burmester dyad of the plate; the 3R chain O-A-F is a 4-pose
dyad of the plate seen from the carrier (phases = the carrier's clockwise turns). Both
families are traced completely (``synthesis``). Each chain is first held to its own
ranges (and the 3R chain to an increasing relative angle: the gears never reverse); the
survivors are paired into five-bars, and every pair is judged over a whole turn by
``judge_candidates``, ``CHUNK`` pairs at a time. The feasible pairs are ranked by their
smallest closure margin.

When no pair is feasible with the least-bending relative angles, the pairs are judged again with the
relative angles held to the conditions (``hold`` of ``judge_candidates``): a problem with a subset of
another's return points then keeps every five-bar the other keeps, so it is never empty where the
other is not. A region that had to hold says so (``Region.held``).

The pairs grow as the square of ``[region] samples`` (both families grow linearly), and
without ``[ranges]`` every dyad within ``radius_mm`` is kept: 2000 samples then pair 3860 B-E
with 626 A-F dyads of the example, 2.4 million five-bars. Each judged five-bar is a
``Candidate`` (tens of microseconds and about a kilobyte), so more than ``PAIR_LIMIT`` are
refused up front with the sampling that would fit.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from transplanter.api_arguments import require_problem
from transplanter.burmester.problem import DyadProblem
from transplanter.burmester.result import Synthesis
from transplanter.burmester.synthesis import synthesize
from transplanter.errors import ProblemError
from transplanter.fivebar.candidate import Candidate, judge_candidates
from transplanter.fivebar.linkage import from_hinges
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.geometry.dyad import Link
from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.poses import carry

#: Five-bars judged in one set of arrays (bounds the memory: CHUNK x 720 turns per array).
CHUNK = 512
#: Most five-bars the region judges (measured: about 6 s and 300 MB on a loaded 2-core machine).
PAIR_LIMIT = 200_000


@dataclass(frozen=True)
class ChainFamily:
    """One sampled dyad family: fixed-side and moving-side hinges in pose 1, and which survive."""

    synthesis: Synthesis
    fixed: np.ndarray        # B (2R) or A (3R), (N, 2)
    moving: np.ndarray       # E (2R) or F (3R), (N, 2)
    kept: np.ndarray         # bool (N,): within ranges and free of the chain's own defects
    reasons: dict            # why dyads were dropped: condition -> count
    shortfalls: dict         # range name -> how far each dyad is outside it (0 inside), (N,)
    measures: dict           # range name -> each dyad's value of it (mm), (N,)


@dataclass(frozen=True)
class Region:
    receiving: ChainFamily   # 2R chain B-E
    carrier: ChainFamily     # 3R chain O-A-F
    candidates: list[Candidate]   # every pair, feasible ones first, best first
    pair_defects: dict            # condition -> number of pairs it removed (first failing condition)
    held: bool = False            # the relative angles were held (``judge_candidates``): none met them unheld

    @property
    def feasible(self) -> list[Candidate]:
        return [c for c in self.candidates if c.feasible]


def _family(synthesis: Synthesis) -> tuple[np.ndarray, np.ndarray]:
    dyads = synthesis.dyads
    return (np.array([d.center for d in dyads]).reshape(-1, 2), np.array([d.circle for d in dyads]).reshape(-1, 2))


def _within(values, bounds):
    return np.ones(len(values), bool) if bounds is None else (values >= bounds[0]) & (values <= bounds[1])


def _shortfall(values, bounds):
    return np.zeros(len(values)) if bounds is None else np.fmax(bounds[0] - values, 0) + np.fmax(values - bounds[1], 0)


def _count(reasons: dict, name: str, mask: np.ndarray, kept: np.ndarray) -> np.ndarray:
    reasons[name] = int(np.sum(kept & ~mask))
    return kept & mask


def chain_families(problem: FiveBarProblem) -> tuple[ChainFamily, ChainFamily]:
    base = DyadProblem(poses=problem.poses, samples=problem.samples, radius_mm=problem.radius_mm,
                       source=problem.source, labels=problem.labels)
    receiving = synthesize(base)
    carrier = synthesize(dataclasses.replace(base, link=Link(np.zeros(2), -problem.carrier_turns)))
    p1 = problem.poses[0, :2]

    families = []
    for synthesis, limits in ((receiving, ("ep", "x_e")), (carrier, ("fp", "x_f"))):
        fixed, moving = _family(synthesis)
        measures = {limits[0]: np.linalg.norm(moving - p1, axis=1), limits[1]: moving[:, 0]}
        reasons: dict[str, int] = {}
        kept = np.ones(len(fixed), bool)
        for name, values in measures.items():
            kept = _count(reasons, f"ranges.{name}", _within(values, problem.ranges.get(name)), kept)
        if synthesis is carrier:
            kept = _count(reasons, "order (relative angle not increasing through the key poses)",
                          _increasing_relative_angle(problem, fixed, moving), kept)
        shortfalls = {name: _shortfall(values, problem.ranges.get(name)) for name, values in measures.items()}
        families.append(ChainFamily(synthesis, fixed, moving, kept, reasons, shortfalls, measures))
    return families[0], families[1]


def _increasing_relative_angle(problem: FiveBarProblem, a1: np.ndarray, f1: np.ndarray) -> np.ndarray:
    """rho_i = theta2_i - theta1_i at the key poses, for every 3R dyad: strictly increasing (mod 2 pi from rho_1)."""
    turns = problem.carrier_turns
    theta1 = np.arctan2(a1[:, 1], a1[:, 0])[:, None] - turns
    a = np.hypot(a1[:, 0], a1[:, 1])[:, None, None] * np.stack([np.cos(theta1), np.sin(theta1)], -1)
    f = carry(problem.poses, f1)
    rho = np.arctan2(f[..., 1] - a[..., 1], f[..., 0] - a[..., 0]) - theta1
    steps = np.mod(rho - rho[:, :1], TWO_PI)
    return np.all(np.diff(steps, axis=1) > 0, axis=1)


def _check_pair_count(problem: FiveBarProblem, receiving: ChainFamily, carrier: ChainFamily):
    kept = int(receiving.kept.sum()), int(carrier.kept.sum())
    pairs = kept[0] * kept[1]
    if pairs > PAIR_LIMIT:
        fitting = int(problem.samples * np.sqrt(PAIR_LIMIT / pairs))
        unranged = "" if problem.ranges else "; without [ranges] every dyad within region.radius_mm is kept"
        raise ProblemError(
            f"{problem.source}: region.samples = {problem.samples}: expected at most about {fitting} here: "
            f"{kept[0]} B-E x {kept[1]} A-F dyads make {pairs} five-bars to judge, more than the {PAIR_LIMIT} "
            f"the region judges (they grow as samples^2{unranged}); lower region.samples or give narrower [ranges]")


def _judged_pairs(problem: FiveBarProblem, receiving: ChainFamily, carrier: ChainFamily, pairs: np.ndarray,
                  hold: bool) -> list[Candidate]:
    candidates = []
    for chunk in np.array_split(pairs, np.arange(CHUNK, len(pairs), CHUNK)):
        i, j = chunk[:, :1], chunk[:, 1:]
        mech = from_hinges(problem.poses[0], receiving.fixed[i], receiving.moving[i], carrier.fixed[j],
                           carrier.moving[j])
        candidates += judge_candidates(problem, mech, check_ranges=False, hold=hold)
    return candidates


def solution_region(problem: FiveBarProblem, hold: bool | None = None) -> Region:
    """The region of ``problem``; ``hold``: None holds the relative angles only when no pair is feasible
    without (the module docstring), True always, False never (a quick look, e.g. while sampling poses)."""
    require_problem(problem, FiveBarProblem, "fivebar")
    receiving, carrier = chain_families(problem)
    _check_pair_count(problem, receiving, carrier)
    pairs = np.stack(np.meshgrid(np.flatnonzero(receiving.kept), np.flatnonzero(carrier.kept), indexing="ij"),
                     -1).reshape(-1, 2)
    held = bool(hold)
    candidates = _judged_pairs(problem, receiving, carrier, pairs, held)
    if hold is None and not any(candidate.feasible for candidate in candidates):
        held, candidates = True, _judged_pairs(problem, receiving, carrier, pairs, True)
    defects: dict[str, int] = {}
    for candidate in candidates:
        if candidate.defects:
            name = candidate.defects[0].split(":")[0]
            defects[name] = defects.get(name, 0) + 1
    margins = np.array([candidate.min_margin for candidate in candidates], float)
    infeasible = np.array([bool(candidate.defects) for candidate in candidates], bool)
    order = np.lexsort((-np.nan_to_num(margins, nan=-np.inf), infeasible))     # stable: ties keep pair order
    return Region(receiving, carrier, [candidates[k] for k in order], defects, held)

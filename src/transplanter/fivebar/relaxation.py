"""What to change when no pair of the solution region is a feasible five-bar.

Of a pair's conditions, two are the designer's limits rather than the key poses' own geometry:
the total ratio bounds (``[conditions] ratio``) and the closure floor
(``[conditions] min_closure_margin``). A pair that fails on those alone is admitted by moving the
limit to the pair's own value; ``relaxation`` finds the pair that needs the least change
(relative: log of the ratio span's growth, log of the floor's drop) and gives the new values,
rounded outward to three significant digits so that they do admit it. Pairs that fail on the
assembly branch, the crank, the order of the relative angle, the return stroke or monotonicity
are not fixed by a limit: the hint then says what the ranges and the region leave to pair.
"""
from __future__ import annotations

import numpy as np

from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import Region

#: The defects (their names before the colon) that a limit of ``[conditions]`` decides.
LIMITS = {"ratio", "closure"}


def _outward(value: float, up: bool) -> float:
    """``value`` to three significant digits, rounded up or down."""
    scale = 10.0 ** (np.floor(np.log10(abs(value))) - 2)
    return float((np.ceil if up else np.floor)(value / scale) * scale)


def _text(value) -> str:
    return f"[{value[0]:g}, {value[1]:g}]" if isinstance(value, list) else f"{value:g}"


def relaxation(problem: FiveBarProblem, region: Region) -> dict:
    """The least change of ``[conditions]`` that admits a pair of ``region`` (field -> new value:
    ``conditions.ratio`` [low, high], ``conditions.min_closure_margin``), with the pair's index in
    ``region.candidates`` under ``"candidate"``; empty when every pair fails on something else."""
    best, best_cost = {}, np.inf
    low, high = problem.ratio_bounds
    for index, candidate in enumerate(region.candidates):
        kinds = {defect.split(":")[0] for defect in candidate.defects}
        if not kinds or not kinds <= LIMITS or ("closure" in kinds and not candidate.min_margin > 0):
            continue            # a margin <= 0: the loop does not close somewhere, which no floor admits
        change: dict[str, object] = {"candidate": index}
        cost = 0.0
        if "ratio" in kinds:
            wanted = (min(low, candidate.ratio_range[0]), max(high, candidate.ratio_range[1]))
            change["conditions.ratio"] = [_outward(wanted[0], False), _outward(wanted[1], True)]
            cost += np.log(wanted[1] / wanted[0]) - np.log(high / low)
        if "closure" in kinds:
            change["conditions.min_closure_margin"] = _outward(candidate.min_margin, False)
            cost += np.log(problem.min_closure_margin / candidate.min_margin)
        if cost < best_cost:
            best, best_cost = change, cost
    return best


def relaxation_hint(problem: FiveBarProblem, region: Region) -> str:
    """One sentence on what to change (``relaxation``), or on what the ranges and the region leave."""
    change = relaxation(problem, region)
    if change:
        candidate = region.candidates[change["candidate"]].mech
        now = {"conditions.ratio": list(problem.ratio_bounds),
               "conditions.min_closure_margin": problem.min_closure_margin}
        edits = ", ".join(f"{field} = {_text(value)} (now {_text(now[field])})" for field, value in change.items()
                          if field != "candidate")
        return (f"the pair with B ({candidate.hinge_b[0]:.1f}, {candidate.hinge_b[1]:.1f}), OA "
                f"{candidate.carrier_length:.1f} fails only on limits; it passes with {edits}")
    kept = [(int(family.kept.sum()), len(family.fixed), name)
            for family, name in ((region.receiving, "B-E"), (region.carrier, "A-F"))]
    return ("every pair fails on the key poses' own conditions, which no limit changes; the ranges and "
            f"region keep {', '.join(f'{k} of {n} {name} dyads' for k, n, name in kept)}: widen [ranges] or "
            "region.radius_mm, or move the key poses")

"""A given five-bar judged with its given motion rho(c) (the gears' relative angle, as design.toml of a run
holds it) instead of a fitted one: P at the key poses and the return points where the motion puts the rod,
and the whole turn on the verification's grid (``verification.TURN_SAMPLES``), so a design read back from
its run reproduces the run's key-pose errors, closure margin and ratio range.

A condition is met within a tolerance relative to the problem: ranges within ``range_slack`` (mm, from the
problem's reach), the closure margin within ``MARGIN_FLOOR_SLACK`` of its floor (as ``verification``)."""
from __future__ import annotations

import numpy as np

from transplanter.fivebar.candidate import (
    BRANCH,
    CRANK,
    GRID,
    Candidate,
    closure_defect,
    crank_exists,
    monotonic_defect,
    range_defect,
    ranges_outside,
    ratio_defect,
)
from transplanter.fivebar.linkage import FiveBar, assembly_branch
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, ratio_range
from transplanter.fivebar.return_stroke import ReturnStroke
from transplanter.fivebar.verification import MARGIN_FLOOR_SLACK, TURN_SAMPLES
from transplanter.geometry.planar import TWO_PI


def pose_errors(mech: FiveBar, relative: RelativeAngle, poses: np.ndarray,
                turns: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """|P - P_i| (mm) and the plate-angle error (deg) at each pose with the rod where the motion puts it."""
    state = mech.forward(turns, relative.evaluate(turns))
    return (np.linalg.norm(state["p"] - poses[:, :2], axis=1),
            np.degrees(np.angle(np.exp(1j * (state["direction"] - poses[:, 2])))))


def judge_motion(problem: FiveBarProblem, mech: FiveBar, relative: RelativeAngle, return_turns: np.ndarray,
                 range_slack: float) -> Candidate:
    """The conditions of ``candidate`` for a mechanism moved by a given motion: ranges, the assembly branch,
    the crank, the return points (within the problem's return tolerance), rho' > 0, the ratio bounds and the
    closure margin over the turn."""
    key_rho = relative.evaluate(problem.carrier_turns)
    values, outside = ranges_outside(problem, mech.as_batch(), range_slack)
    defects = [range_defect(key, float(np.ravel(values[key])[0]), problem.ranges[key])
               for key, bad in outside.items() if bad[0]]
    e, f = mech.plate_points(problem.poses)
    if np.any(assembly_branch(mech.hinge_b, e, f) != mech.branch):
        defects.append(BRANCH)
    if not crank_exists(mech):
        defects.append(CRANK)
    state = mech.forward(return_turns, relative.evaluate(return_turns))
    misses = np.linalg.norm(state["p"] - problem.return_points, axis=1)
    defects += [f"return point {k + 1}: P misses it by {miss:.3g} mm (tolerance {problem.return_tolerance_mm:g} mm)"
                for k, miss in enumerate(misses) if not miss <= problem.return_tolerance_mm]
    grid = np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)
    margin = float(np.min(mech.forward(grid, relative.evaluate(grid))["margin"]))
    slope = relative.evaluate(grid, 1)
    low, high = ratio_range(slope)
    if not slope.min() > 0:
        defects.append(monotonic_defect(relative.evaluate(GRID, 1)))      # its spans on the candidates' grid
    elif not problem.ratio_bounds[0] <= low <= high <= problem.ratio_bounds[1]:
        defects.append(ratio_defect(low, high, problem.ratio_bounds))
    if not margin >= problem.min_closure_margin * (1 - MARGIN_FLOOR_SLACK):
        defects.append(closure_defect(margin, problem.min_closure_margin))
    stroke = ReturnStroke(return_turns, relative.evaluate(return_turns), state["direction"])
    return Candidate(mech, key_rho, defects, stroke, relative, margin, (float(low), float(high)))

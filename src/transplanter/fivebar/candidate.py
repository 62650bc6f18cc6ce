"""One candidate five-bar judged over a whole turn: key-pose relative angles, return stroke,
fitted relative angle, and the conditions a gear-driven five-bar must meet.

Conditions (each failure is named in ``defects``):
- the relative angle rho increases through the key poses (order: the gears never reverse);
- the B-E-F assembly is the same at the four key poses (branch);
- the carrier can turn fully (five-bar crank existence, see ``crank_exists``);
- the return points have a consistent inverse kinematics (``return_stroke``);
- the fitted rho(c) is strictly increasing, with the ratio i0 = 1/rho' inside the bounds;
- the chain closes all round with sin^2(angle EBF) above the margin (eq 10).
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from transplanter.fivebar.linkage import FiveBar, assembly_branch
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, fit_relative_angle, negative_intervals, ratio_range
from transplanter.fivebar.return_stroke import ReturnStroke, solve_return_stroke

TWO_PI = 2 * np.pi
#: Carrier turns at which the whole-turn conditions are checked.
GRID = np.linspace(0, TWO_PI, 720, endpoint=False)


@dataclass(frozen=True)
class Candidate:
    mech: FiveBar
    key_relative_angles: np.ndarray
    defects: list[str] = field(default_factory=list)
    stroke: ReturnStroke | None = None
    relative_angle: RelativeAngle | None = None
    min_margin: float = float("nan")
    ratio_range: tuple[float, float] = (float("nan"), float("nan"))

    @property
    def feasible(self) -> bool:
        return not self.defects


def crank_exists(mech: FiveBar) -> bool:
    """The carrier turns fully iff the chain A-F-E-B (L2, L3, L4) spans every |AB| in
    [|L5 - L1|, L5 + L1]: at most L2 + L3 + L4, at least 2 max(L2, L3, L4) - (L2 + L3 + L4)."""
    chain = np.array([mech.rod_length, mech.link_length, mech.receiving_length])
    frame = float(np.hypot(*mech.hinge_b))
    return frame + mech.carrier_length <= chain.sum() and abs(frame - mech.carrier_length) >= 2 * chain.max() - chain.sum()


def range_values(problem: FiveBarProblem, mech: FiveBar) -> dict:
    """The quantities that ``[ranges]`` limit, for this mechanism."""
    e, f = mech.plate_points(problem.poses[0])
    return {"ep": mech.ep, "fp": mech.fp, "x_e": float(e[0]), "x_f": float(f[0])}


def range_violations(problem: FiveBarProblem, mech: FiveBar) -> list[str]:
    values = range_values(problem, mech)
    return [f"ranges.{key} = {values[key]:.2f} outside [{low:g}, {high:g}]"
            for key, (low, high) in problem.ranges.items() if not low <= values[key] <= high]


def whole_turn(mech: FiveBar, relative: RelativeAngle, grid: np.ndarray = GRID) -> tuple[float, np.ndarray]:
    """Smallest closure margin over the grid, and rho' on it."""
    state = mech.forward(grid, relative.evaluate(grid))
    return float(np.min(state["margin"])), relative.evaluate(grid, 1)


def evaluate_candidate(problem: FiveBarProblem, mech: FiveBar, check_ranges: bool = True) -> Candidate:
    turns = problem.carrier_turns
    rho = mech.relative_angle_at(problem.poses, turns)
    rho = rho[0] + np.mod(rho - rho[0], TWO_PI)
    defects = range_violations(problem, mech) if check_ranges else []
    if np.any(np.diff(rho) <= 0):
        defects.append("order: the relative angle does not increase through the key poses "
                       f"({', '.join(f'{v:.1f}' for v in np.degrees(rho))} deg)")
    e, f = mech.plate_points(problem.poses)
    if np.any(assembly_branch(mech.hinge_b, e, f) != mech.branch):
        defects.append("branch: the B-E-F assembly differs between key poses")
    if not crank_exists(mech):
        defects.append("crank: the carrier cannot turn fully")
    if defects:
        return Candidate(mech, rho, defects)
    stroke = solve_return_stroke(mech, problem.return_points, turns[-1], rho[0], rho[-1], problem.poses[-1, 2])
    if stroke is None:
        return Candidate(mech, rho, ["return: no assembly reaches the return points in order"])
    relative = fit_relative_angle(np.r_[turns, stroke.carrier_turns], np.r_[rho, stroke.relative_angles],
                                  problem.spline_count)
    margin, slope = whole_turn(mech, relative)
    ratio = ratio_range(slope)
    if slope.min() <= 0:
        spans = ", ".join(f"{a:.1f}-{b:.1f}" for a, b in negative_intervals(GRID, slope))
        defects.append(f"monotonic: rho' <= 0 (down to {slope.min():.3f}) for carrier turns {spans} deg")
    elif ratio[0] < problem.ratio_bounds[0] or ratio[1] > problem.ratio_bounds[1]:
        defects.append(f"ratio: i0 spans [{ratio[0]:.3f}, {ratio[1]:.3f}], outside {list(problem.ratio_bounds)}")
    if not margin >= problem.min_closure_margin:
        defects.append(f"closure: min sin^2(EBF) = {margin:.4f} < {problem.min_closure_margin:g}")
    return Candidate(mech, rho, defects, stroke, relative, margin, ratio)

"""The monotonicity criterion of the reverse-gear-design paper, checked along the whole path.

A planetary train can draw the path only if (i) the carrier, which turns uniformly, advances
one way: c'(x) > 0; (ii) the planet never turns back against the carrier (the gears never
reverse): chi'(c) = -d gamma / d theta > 0, with d gamma / d theta from the generated
``planetary_relative_per_carrier``; (iii) both make exactly one turn per cycle, so every
pitch curve closes. A failure is reported as intervals of u = x / 2 pi (point k of the input
at u = k / N) with the worst value, and ``fix_hints`` says which change would pass.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.closed_trajectory import ClosedTrajectory
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.arm_inverse import BRANCH_NAMES, DIRECTION_NAMES, ArmMotion, solve_arm, touched_circle


@dataclass(frozen=True)
class Violation:
    condition: str          # "carrier", "gears" or "turns"
    u_start: float
    u_end: float
    worst: float            # the smallest c'(x) or chi'(c) in the interval, or the turn count
    message: str


def _runs(failing: np.ndarray) -> list[tuple[int, int]]:
    """(first, last) index of each run of True, the runs that wrap round joined."""
    if not failing.any():
        return []
    edges = np.flatnonzero(np.diff(np.r_[0, failing.astype(int), 0]))
    runs = [(int(a), int(b) - 1) for a, b in zip(edges[::2], edges[1::2], strict=True)]
    if len(runs) > 1 and runs[0][0] == 0 and runs[-1][1] == len(failing) - 1:
        runs = [(runs[-1][0], runs[0][1])] + runs[1:-1]
    return runs


def _where(motion: ArmMotion, x: float) -> str:
    point = motion.trajectory.evaluate(x)
    return f"u = {x / TWO_PI:.4f} ({point[0]:.1f}, {point[1]:.1f})"


def violations(motion: ArmMotion) -> list[Violation]:
    found = []
    carrier, planet = motion.net_turns()
    if len(motion.touches) % 2:
        found.append(Violation("turns", 0.0, 1.0, float(len(motion.touches)),
                               f"the path touches the reach circles {len(motion.touches)} times: the branch switches "
                               "at each touch, so an odd count leaves the arm on the other branch after one cycle"))
    elif abs(carrier - 1) > 1e-6 or abs(planet - 1) > 1e-6:
        found.append(Violation("turns", 0.0, 1.0, carrier,
                               f"per cycle the carrier turns {carrier:+.3f} and the planet {planet:+.3f} turns "
                               "against it in the carrier's direction; both must turn exactly +1 "
                               "for the pitch curves to close"))
    x = motion.grid
    (c1, _, _), (h1, _, _) = motion.path_rates(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        slope = np.where(c1 > 0, h1 / c1, np.inf)
    for condition, values, what in (
            ("carrier", c1, "the carrier would stop or turn back (c' = {worst:.3g} rad per rad of x = 2 pi u)"),
            ("gears", slope, "the planet would stop or turn back against the carrier (chi' = {worst:.3g}): "
                             "the gears would reverse")):
        for first, last in _runs(values <= 0):
            span = np.r_[first:last + 1] if first <= last else np.r_[first:len(x), 0:last + 1]
            worst = float(values[span].min())
            found.append(Violation(condition, float(x[first] / TWO_PI), float(x[last] / TWO_PI), worst,
                                   f"from {_where(motion, x[first])} to {_where(motion, x[last])}: "
                                   + what.format(worst=worst)))
    return found


def stationary_radii(motion: ArmMotion) -> list[str]:
    """Extremes of |P| away from both reach circles: there d gamma / d theta = 0 (the gears stop)."""
    return [f"|P| = {e.radius:.3f} mm at {_where(motion, e.parameter)}" for e in motion.trajectory.radial_extremes()
            if not touched_circle(e, motion.carrier_length, motion.arm_length)]


def fix_hints(trajectory: ClosedTrajectory, motion: ArmMotion, derived_lengths: tuple[float, float]) -> list[str]:
    """Changes that would pass the criterion, each tried on the same path."""
    lengths, d, b = (motion.carrier_length, motion.arm_length), motion.direction, motion.start_branch
    trials = [(f"start on the {BRANCH_NAMES[-b]} branch", (*lengths, d, -b)),
              (f"turn the carrier {DIRECTION_NAMES[-d]}", (*lengths, -d, b)),
              (f"turn the carrier {DIRECTION_NAMES[-d]} and start on the {BRANCH_NAMES[-b]} branch",
               (*lengths, -d, -b))]
    if not np.allclose(derived_lengths, lengths, rtol=1e-9, atol=0):
        trials += [(f"carrier_length = {derived_lengths[0]:.4f} and arm_length = {derived_lengths[1]:.4f} mm "
                    "(the rice-transplanter paper eq 1-2: the arm straightens at the farthest point and folds "
                    "at the nearest), "
                    f"the carrier turning {DIRECTION_NAMES[direction]}, starting on the {BRANCH_NAMES[branch]} branch",
                    (*derived_lengths, direction, branch))
                   for direction in (d, -d) for branch in (b, -b)]
    hints = [text for text, arguments in trials if not violations(solve_arm(trajectory, *arguments))]
    stationary = stationary_radii(motion)
    if stationary and not hints:
        hints.append("the distance from the pivot is stationary away from the reach circles at "
                     + "; ".join(stationary) + ": the gears stop there whatever the train; reshape the path so "
                     "|P| rises monotonically from its nearest to its farthest point and back, or move the pivot")
    if not hints:
        hints.append("none of: the other start branch, the other direction, the lengths from the path's extremes; "
                     "the path itself must change where it fails (the carrier can only advance, the gears only "
                     "one way)")
    return hints

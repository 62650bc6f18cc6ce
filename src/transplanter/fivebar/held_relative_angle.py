"""The least-bending relative angle through the points that keeps the conditions, where the least-bending
one through them does not.

The region fits rho(c) through the key poses and a return stroke as the least-bending spline
(``fit_relative_angle``). Through few points it is free over long stretches, and there it may leave the
band in which the five-bar closes with its margin, or turn faster or slower than the ratio bounds allow,
though another spline through the same points keeps both: for one, the spline of a problem with more
return points on the same passes. Whether one exists is a convex question: the spline's values and slopes
at the carrier turns of a grid are linear in its control values, and the conditions bound them there
(``closure_band`` with F on the side of line AB it takes at the points; 1 / i_max <= rho' <= 1 / i_min).
So the held relative angle is the least-bending spline through the points within those bounds at the grid
turns, a QP (``solve.qp``) whose bound rows are added where the last solution breaks them (the exchange
method): rows left out only widen the QP, so an infeasible QP proves that no spline keeps them.

Dropping return points removes equality rows and widens the QP: a relative angle held for a problem is a
feasible point for every problem with a subset of its return points on the same passes.
"""
from __future__ import annotations

import functools

import numpy as np

from transplanter.errors import SolverError
from transplanter.fivebar.closure_band import closure_band, rod_side
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, bending_matrix, fit_relative_angle, interpolation_rows
from transplanter.fivebar.return_stroke import ReturnStroke
from transplanter.geometry.periodic_bspline import basis_matrix
from transplanter.geometry.planar import TWO_PI
from transplanter.solve import exchange, periodic_peaks
from transplanter.solve.qp import solve_qp

#: The bounds are held this fraction inside the conditions, so the forward check that follows meets them.
INSET = 1e-6
#: QP solves before a relative angle that still breaks a bound between held turns counts as not held.
ROUNDS = 12


@functools.lru_cache(maxsize=8)
def turn_rows(count: int, points: int) -> tuple[np.ndarray, np.ndarray]:
    """(values, slopes): rows giving S(c) - S(0) and S'(c) from q[1:] at ``points`` evenly spaced carrier turns
    (from 0), for ``count`` control values; computed once (read-only)."""
    turns = np.linspace(0, TWO_PI, points, endpoint=False)
    rows = ((basis_matrix(turns, count) - basis_matrix(np.zeros(1), count))[:, 1:],
            basis_matrix(turns, count, 1)[:, 1:])
    for matrix in rows:
        matrix.flags.writeable = False
    return rows


def hold_relative_angle(problem: FiveBarProblem, mech: FiveBar, key_rho: np.ndarray, stroke: ReturnStroke,
                        points: int) -> RelativeAngle | None:
    """The least-bending rho(c) through the key poses' (``key_rho``) and the return stroke's relative angles
    with the closure margin and rho' within their bounds at ``points`` evenly spaced carrier turns, for one
    mechanism; None when no spline of ``problem.spline_count`` control values has them (or F changes sides of
    line AB between the points, which the band does not follow)."""
    turns, rho = np.r_[problem.carrier_turns, stroke.carrier_turns], np.r_[key_rho, stroke.relative_angles]
    sides = rod_side(mech, turns, rho)
    if not np.all(sides == sides[0]):
        return None
    grid = np.linspace(0, TWO_PI, points, endpoint=False)
    low, high = closure_band(mech, grid, problem.min_closure_margin * (1 + INSET), sides[0],
                             np.interp(grid, np.r_[turns, TWO_PI], np.r_[rho, rho[0] + TWO_PI]))
    if np.isnan(low).any():
        return None
    slowest, fastest = 1 / problem.ratio_bounds[1] * (1 + INSET), 1 / problem.ratio_bounds[0] * (1 - INSET)
    count = problem.spline_count
    rows, target = interpolation_rows(turns, rho, count)
    values, slopes = turn_rows(count, points)
    offset = rho[0] + grid
    bending = bending_matrix(count)[1:, 1:]

    def shortfall(x: np.ndarray) -> np.ndarray:
        angle, slope = values @ x + offset, 1 + slopes @ x
        return np.fmax.reduce([low - angle, angle - high, slowest - slope, slope - fastest])

    def solve(held: np.ndarray, _) -> np.ndarray:
        held = np.unique(held)
        return solve_qp(bending, np.zeros(count - 1), np.r_[rows, values[held], slopes[held]],
                        np.r_[target, low[held] - offset[held], np.full(held.size, slowest - 1)],
                        np.r_[target, high[held] - offset[held], np.full(held.size, fastest - 1)])

    def worst(x: np.ndarray) -> np.ndarray:
        return periodic_peaks(shortfall(x))

    try:
        x, _ = exchange(solve, worst, worst(fit_relative_angle(turns, rho, count).coefficients[1:]), ROUNDS)
    except SolverError:
        return None
    return None if worst(x).size else RelativeAngle(rho[0], np.r_[0.0, x])

"""Angle of connecting rod I relative to the carrier against the carrier's turn (seed 000 Figure 9).

The carrier turns clockwise by c from pose 1. The rod's angle relative to the carrier,
rho = theta2 - theta1, must grow by exactly 2 pi per turn for the rod to come back, so

    rho(c) = rho1 + c + S(c) - S(0),

with S a periodic cubic B-spline (``periodic_bspline``). The gear train realises rho(c);
its total ratio is i0 = dc / drho = 1 / rho'(c) (eq 11), finite and positive only while
rho is strictly increasing.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.geometry.periodic_bspline import TWO_PI, basis_matrix, evaluate, knots

#: Grid on which the bending energy int S''^2 dc is summed.
BENDING_SAMPLES = 720


@dataclass(frozen=True)
class RelativeAngle:
    """rho(c) in radians; ``coefficients`` are the spline's control values (radians)."""

    rho1: float
    coefficients: np.ndarray

    @property
    def count(self) -> int:
        return len(self.coefficients)

    @property
    def knots(self) -> np.ndarray:
        return knots(self.count)

    def evaluate(self, c, order: int = 0) -> np.ndarray:
        """rho or its ``order``-th derivative in c, at any carrier turns c (rad)."""
        c = np.asarray(c, float)
        spline = evaluate(c, self.coefficients, order)
        if order == 0:
            return spline + self.rho1 + c - evaluate(0.0, self.coefficients)
        return spline + 1.0 if order == 1 else spline


def ratio_range(slope: np.ndarray) -> tuple[float, float]:
    """(min, max) of the total ratio i0 = 1 / rho' (eq 11) from rho' samples; NaN when rho is not increasing."""
    if slope.min() <= 0:
        return float("nan"), float("nan")
    return float(1 / slope.max()), float(1 / slope.min())


def negative_intervals(turns: np.ndarray, values: np.ndarray) -> list[tuple[float, float]]:
    """Carrier-turn intervals (deg) of a periodic grid where ``values`` <= 0."""
    bad = values <= 0
    if not bad.any():
        return []
    if bad.all():
        return [(0.0, 360.0)]
    starts = np.flatnonzero(bad & ~np.roll(bad, 1))
    ends = np.flatnonzero(bad & ~np.roll(bad, -1))
    intervals = []
    for start in starts:
        end = ends[np.argmin((ends - start) % len(bad))]      # the run's end, maybe past the wrap
        intervals.append((float(np.degrees(turns[start])), float(np.degrees(turns[end]))))
    return intervals


def bending_matrix(count: int) -> np.ndarray:
    """G with q^T G q = int_0^2pi S''(c)^2 dc (midpoint sum; exact for the piecewise-linear S'')."""
    grid = (np.arange(BENDING_SAMPLES) + 0.5) * TWO_PI / BENDING_SAMPLES
    second = basis_matrix(grid, count, 2)
    return second.T @ second * (TWO_PI / BENDING_SAMPLES)


def fit_relative_angle(carrier_turns: np.ndarray, rho: np.ndarray, count: int) -> RelativeAngle:
    """The least-bending spline through (c_j, rho_j); c_0 = 0 is pose 1.

    Interpolation is exact (a linear KKT system); the remaining freedom of the ``count``
    control values minimises int S''^2. The constant mode is fixed by q_0 = 0.
    """
    c, rho = np.asarray(carrier_turns, float), np.asarray(rho, float)
    if len(c) > count:
        raise InfeasibleError(f"relative angle: {len(c)} points need at least {len(c)} spline control values, "
                              f"got {count}")
    target = rho[1:] - rho[0] - c[1:]
    rows = (basis_matrix(c[1:], count) - basis_matrix(np.zeros(1), count))[:, 1:]
    bending = bending_matrix(count)[1:, 1:]
    n, m = bending.shape[0], len(target)
    kkt = np.zeros((n + m, n + m))
    kkt[:n, :n], kkt[:n, n:], kkt[n:, :n] = bending, rows.T, rows
    solution = np.linalg.solve(kkt, np.r_[np.zeros(n), target])
    return RelativeAngle(float(rho[0]), np.r_[0.0, solution[:n]])

"""Angle of connecting rod I relative to the carrier against the carrier's turn (Wang et al. 2025 Figure 9).

The carrier turns clockwise by c from pose 1. The rod's angle relative to the carrier,
rho = theta2 - theta1, must grow by exactly 2 pi per turn for the rod to come back, so

    rho(c) = rho1 + c + S(c) - S(0),

with S a periodic cubic B-spline (``periodic_bspline``). The gear train realises rho(c);
its total ratio is i0 = dc / drho = 1 / rho'(c) (eq 11), finite and positive only while
rho is strictly increasing.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.geometry.periodic_bspline import basis_matrix, evaluate, knots
from transplanter.geometry.planar import TWO_PI

#: Grid on which the bending energy int S''^2 dc is summed.
BENDING_SAMPLES = 720


@dataclass(frozen=True)
class RelativeAngle:
    """rho(c) in radians; ``coefficients`` are the spline's control values (radians).

    A batch holds ``rho1`` of shape (K, 1) and ``coefficients`` (K, N): ``evaluate`` on a
    row of turns then gives (K, len(c)).
    """

    rho1: float | np.ndarray
    coefficients: np.ndarray

    @property
    def count(self) -> int:
        return np.shape(self.coefficients)[-1]

    @property
    def knots(self) -> np.ndarray:
        return knots(self.count)

    def evaluate(self, c, order: int = 0) -> np.ndarray:
        """rho or its ``order``-th derivative in c, at any carrier turns c (rad)."""
        c = np.asarray(c, float)
        spline = evaluate(c, self.coefficients, order)
        if order == 0:
            return spline + self.rho1 + c - np.reshape(evaluate(0.0, self.coefficients), np.shape(self.rho1))
        return spline + 1.0 if order == 1 else spline


def ratio_range(slope: np.ndarray) -> tuple:
    """(min, max) of the total ratio i0 = 1 / rho' (eq 11) from rho' samples (last axis); NaN when rho is
    not increasing. Floats for one row of samples, arrays (K,) for K rows."""
    lowest = slope.min(axis=-1)
    with np.errstate(divide="ignore"):
        low = np.where(lowest > 0, 1 / slope.max(axis=-1), np.nan)
        high = np.where(lowest > 0, 1 / lowest, np.nan)
    return (float(low), float(high)) if slope.ndim == 1 else (low, high)


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


@functools.lru_cache(maxsize=8)
def bending_matrix(count: int) -> np.ndarray:
    """G with q^T G q = int_0^2pi S''(c)^2 dc (midpoint sum; exact for the piecewise-linear S'').
    Computed once per ``count`` (read-only): every fit of the region uses it."""
    grid = (np.arange(BENDING_SAMPLES) + 0.5) * TWO_PI / BENDING_SAMPLES
    second = basis_matrix(grid, count, 2)
    matrix = second.T @ second * (TWO_PI / BENDING_SAMPLES)
    matrix.flags.writeable = False
    return matrix


def interpolation_rows(carrier_turns: np.ndarray, rho: np.ndarray, count: int) -> tuple[np.ndarray, np.ndarray]:
    """(rows, target): the spline passes through (c_j, rho_j) iff rows @ q[1:] = target (q_0 = 0; c_0 = 0 is
    pose 1, whose rho_0 is rho1). Batched like the points: rows (..., p - 1, count - 1)."""
    if carrier_turns.shape[-1] > count:
        raise InfeasibleError(f"relative angle: {carrier_turns.shape[-1]} points need at least "
                              f"{carrier_turns.shape[-1]} spline control values, got {count}")
    target = rho[..., 1:] - rho[..., :1] - carrier_turns[..., 1:]
    return (basis_matrix(carrier_turns[..., 1:], count) - basis_matrix(np.zeros(1), count))[..., 1:], target


def fit_relative_angle(carrier_turns: np.ndarray, rho: np.ndarray, count: int) -> RelativeAngle:
    """The least-bending spline through (c_j, rho_j); c_0 = 0 is pose 1.

    Interpolation is exact (a linear KKT system); the remaining freedom of the ``count``
    control values minimises int S''^2. The constant mode is fixed by q_0 = 0. Given
    (K, p) turns and angles, it fits K splines at once (a batch ``RelativeAngle``).
    """
    c, rho = np.asarray(carrier_turns, float), np.asarray(rho, float)
    rows, target = interpolation_rows(c, rho, count)
    bending = bending_matrix(count)[1:, 1:]
    n, m = bending.shape[0], target.shape[-1]
    kkt = np.zeros(c.shape[:-1] + (n + m, n + m))
    kkt[..., :n, :n], kkt[..., :n, n:], kkt[..., n:, :n] = bending, np.swapaxes(rows, -1, -2), rows
    rhs = np.concatenate([np.zeros(target.shape[:-1] + (n,)), target], axis=-1)
    solution = np.linalg.solve(kkt, rhs[..., None])[..., 0]
    coefficients = np.concatenate([np.zeros(target.shape[:-1] + (1,)), solution[..., :n]], axis=-1)
    return RelativeAngle(rho[..., 0] if rho.ndim == 1 else rho[..., :1], coefficients)

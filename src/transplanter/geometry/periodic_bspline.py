"""Uniform periodic cubic B-spline on one turn (Wang et al. 2025 eq 5-6).

With N control values q_i on equally spaced knots (spacing h = 2 pi / N), the Cox-de Boor
recursion of eq (6) gives the same cubic basis function shifted to every knot, so

    S(x) = sum_i q_i beta((x - i h) / h),

beta being the centered cubic B-spline (support [-2, 2], C2), taken periodically. Written
with a backend ``lib`` (numpy or casadi: ``floor``, ``fabs``, ``if_else``) so the same
formula serves the sweeps and the design NLP, where knots may be evaluated at decision
variables. ``tests/geometry/test_periodic_bspline.py`` checks beta against sympy's Cox-de Boor basis.
"""
from __future__ import annotations

from types import SimpleNamespace

import casadi as ca
import numpy as np

from transplanter.geometry.planar import TWO_PI

NUMPY = SimpleNamespace(floor=np.floor, fabs=np.abs, if_else=np.where)
CASADI = SimpleNamespace(floor=ca.floor, fabs=ca.fabs, if_else=ca.if_else)


def kernel(u, order: int = 0, lib=NUMPY):
    """``order``-th derivative of the centered cubic B-spline at u (in knot spacings). The third
    derivative is piecewise constant; at the knots it takes its value from the right, as ``evaluate`` does."""
    if order == 3:
        steps = ((-2, 0.0), (-1, 1.0), (0, -3.0), (1, 3.0), (2, -1.0))
        value = 0 * u
        for edge, left in reversed(steps):
            value = lib.if_else(u < edge, left + 0 * u, value)
        return value
    a = lib.fabs(u)
    sign = lib.if_else(u < 0, -1.0, 1.0)
    inner, outer = [
        (2 / 3 - a**2 + a**3 / 2, (2 - a)**3 / 6),
        (sign * (-2 * a + 1.5 * a**2), -sign * (2 - a)**2 / 2),
        (-2 + 3 * a, 2 - a),
    ][order]
    return lib.if_else(a < 1, inner, lib.if_else(a < 2, outer, 0 * a))


def wrapped_offset(x, knot: int, count: int, lib=NUMPY):
    """(x / h - knot) brought into [-count/2, count/2): the periodic distance to a knot, in spacings."""
    u = x * count / TWO_PI - knot
    return u - count * lib.floor(u / count + 0.5)


def basis(x, count: int, order: int = 0, lib=NUMPY):
    """Rows of basis values (or derivatives d^order/dx^order) at x, one column per knot."""
    scale = (count / TWO_PI) ** order
    return [scale * kernel(wrapped_offset(x, k, count, lib), order, lib) for k in range(count)]


def basis_matrix(x: np.ndarray, count: int, order: int = 0) -> np.ndarray:
    """Numeric basis matrix (len(x), count) for fixed abscissae."""
    return np.stack(basis(np.asarray(x, float), count, order), axis=-1)


#: Segment form: on [k h, (k + 1) h) with t = x / h - k, S = sum_m q_{k-1+m} b_m(t), b = SEGMENT @ (1, t, t^2, t^3).
SEGMENT = np.array([[1, -3, 3, -1], [4, 0, -6, 3], [1, 3, 3, -3], [0, 0, 0, 1]]) / 6


def evaluate(x, coefficients: np.ndarray, order: int = 0) -> np.ndarray:
    """S or its ``order``-th derivative at x (numpy), from the four control values of each segment.

    ``coefficients`` (..., N) may hold a batch of splines: the result is batch + x.shape.
    """
    count = np.shape(coefficients)[-1]
    u = np.asarray(x, float) * count / TWO_PI
    k = np.floor(u)
    t = u - k
    powers = np.stack([np.ones_like(t), t, t**2, t**3], -1)
    for _ in range(order):
        powers = np.stack([0 * t, powers[..., 0], 2 * powers[..., 1], 3 * powers[..., 2]], -1)
    weights = powers @ SEGMENT.T
    index = (k.astype(int)[..., None] + np.arange(-1, 3)) % count
    return np.sum(weights * coefficients[..., index], axis=-1) * (count / TWO_PI) ** order


def knots(count: int) -> np.ndarray:
    return TWO_PI * np.arange(count) / count

"""Piecewise cubic Hermite interpolation: values and slopes at knots, scalar or vector values."""
from __future__ import annotations

import numpy as np


def hermite(knots: np.ndarray, values: np.ndarray, start_slopes: np.ndarray, end_slopes: np.ndarray, x) -> np.ndarray:
    """The cubic Hermite at ``x``: on interval k from values[k] with slope start_slopes[k] to values[k + 1] with
    slope end_slopes[k] (x beyond the knots on the end intervals). ``values`` may be (n,) or (n, d); slopes are
    per unit of ``knots``."""
    x = np.asarray(x, float)
    k = np.clip(np.searchsorted(knots, x, side="right") - 1, 0, len(knots) - 2)
    h = knots[k + 1] - knots[k]
    t = (x - knots[k]) / h
    if values.ndim > 1:
        t, h = t[..., None], h[..., None]
    return ((2 * t**3 - 3 * t**2 + 1) * values[k] + (t**3 - 2 * t**2 + t) * h * start_slopes[k]
            + (-2 * t**3 + 3 * t**2) * values[k + 1] + (t**3 - t**2) * h * end_slopes[k])

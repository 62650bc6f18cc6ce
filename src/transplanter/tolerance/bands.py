"""First-order bands and variance shares from the exact Jacobian of the motion.

With dimension i off by delta_i, P moves by J_i delta_i and the plate turns by j_i delta_i (J_i the
two position rows of the Jacobian, j_i the angle row). The dimensions vary independently with standard
deviations sigma_i (``dimensions``: t_i / sqrt(3) uniform, t_i / 3 normal), so

- position covariance C = sum_i sigma_i^2 J_i J_i^T; its 3-sigma band is 3 sqrt(lambda_max(C)), the
  semi-major axis of the 3-sigma error ellipse (mm);
- angle: 3 sqrt(sum_i sigma_i^2 j_i^2) (deg);
- worst case: sum_i t_i |J_i| (mm) and sum_i t_i |j_i| (deg), every dimension at its limit together;
- the share of dimension i in a pose's variance: sigma_i^2 |J_i|^2 / trace(C) for the position and
  sigma_i^2 j_i^2 / sum for the angle.
"""
from __future__ import annotations

import numpy as np


def largest_eigenvalue(covariance: np.ndarray) -> np.ndarray:
    """lambda_max of symmetric 2 x 2 matrices (..., 2, 2), in closed form."""
    a, b, c = covariance[..., 0, 0], covariance[..., 0, 1], covariance[..., 1, 1]
    return (a + c) / 2 + np.sqrt(((a - c) / 2) ** 2 + b**2)


def position_covariance(jacobian: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """C (..., 2, 2) from position Jacobians (2, ..., n) and standard deviations (n,)."""
    weighted = jacobian * sigma
    return np.einsum("i...k,j...k->...ij", weighted, weighted)


def statistical_bands(jacobian: np.ndarray, sigma: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """3-sigma position band (mm) and angle band (deg) per column, from the motion's Jacobian (rows, T, n)."""
    position = 3 * np.sqrt(largest_eigenvalue(position_covariance(jacobian[:2], sigma)))
    angle = 3 * np.sqrt(np.sum((jacobian[2] * sigma) ** 2, axis=-1))
    return position, np.degrees(angle)


def worst_case_bands(jacobian: np.ndarray, tolerance: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Position (mm) and angle (deg) per column with every dimension at its limit, signs adding up."""
    position = np.sum(np.hypot(jacobian[0], jacobian[1]) * tolerance, axis=-1)
    return position, np.degrees(np.sum(np.abs(jacobian[2]) * tolerance, axis=-1))


def variance_shares(jacobian: np.ndarray, sigma: np.ndarray) -> tuple[np.ndarray, ...]:
    """Each dimension's share (T, n) of the position variance and of the angle variance per column."""
    return tuple(_fractions(part) for part in ((jacobian[0] ** 2 + jacobian[1] ** 2) * sigma**2,
                                               (jacobian[2] * sigma) ** 2))


def relative_difference(value: np.ndarray, reference: np.ndarray) -> np.ndarray:
    """|value / reference - 1|, 0 where both are 0 (nothing moves) and inf where only the reference is."""
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(value == reference, 0.0, np.abs(value / reference - 1))


def _fractions(variances: np.ndarray) -> np.ndarray:
    """Each entry's share of its row's sum (0 in a row of zeros)."""
    total = variances.sum(axis=-1, keepdims=True)
    return np.divide(variances, total, out=np.zeros_like(variances), where=total > 0)

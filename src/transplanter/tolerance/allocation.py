"""Tolerance allocation: the loosest tolerances whose statistical band meets the accuracy the key poses need.

Variables y_i = log t_i, each within ``ALLOCATION_RANGE`` times the dimension's default tolerance;
maximise sum_i y_i (the volume of the tolerance box) subject to, at every key pose k,
9 lambda_max(C_k(t)) <= pose_position_mm^2 and 9 sum_i sigma_i^2 j_ki^2 <= pose_angle^2 (``bands``), with
sigma_i = t_i times the distribution's factor. lambda_max(C) <= q is written as q I - C positive
semidefinite: q - C_xx >= 0, q - C_yy >= 0 and det(q I - C) >= 0, rows smooth where the closed-form
eigenvalue is not (a round ellipse). The Jacobian is the nominal design's, so the rows are
smooth in y and the NLP small (one variable per dimension, two rows per key pose); it goes through the
package's one NLP layer. The result is checked by evaluating the bands at the allocated tolerances.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter.solve import NLPBuilder, Solver
from transplanter.tolerance.bands import statistical_bands
from transplanter.tolerance.dimensions import ALLOCATION_RANGE

#: A requirement counts as binding where the allocated band reaches it within this fraction.
BINDING = 1e-6


@dataclass(frozen=True)
class Allocation:
    """Allocated tolerances (dimension order, their units), the bands they give at the key poses (mm, deg),
    which requirements bind, and the solve's status and iterations."""

    tolerances: np.ndarray
    position_3sigma_mm: np.ndarray
    angle_3sigma_deg: np.ndarray
    binding: tuple[str, ...]
    status: str
    iterations: int


def allocate(key_jacobian: np.ndarray, defaults: np.ndarray, sigma_per_tolerance: float, labels: tuple[str, ...],
             position_mm: float, angle_deg: float) -> Allocation:
    """Loosest tolerances for the key poses' Jacobian (3, K, n) whose 3-sigma bands meet ``position_mm`` and
    ``angle_deg`` at every key pose; ``defaults`` (n,) > 0 set each dimension's range."""
    low, high = np.log(defaults * ALLOCATION_RANGE[0]), np.log(defaults * ALLOCATION_RANGE[1])
    nlp = NLPBuilder()
    y = nlp.variables("log_tolerance", len(defaults), low, high)
    sigma = ca.exp(y) * sigma_per_tolerance
    diagonal_rows, determinant_rows, angle_rows = [], [], []
    for k in range(key_jacobian.shape[1]):
        jx, jy, ja = (ca.DM(key_jacobian[r, k]) for r in range(3))
        # q I - C over q = (position_mm / 3)^2, so the rows are of order one
        a, b, c = (ca.sum1((u * sigma) * (w * sigma)) * 9 / position_mm**2 for u, w in ((jx, jx), (jx, jy), (jy, jy)))
        diagonal_rows += [1 - a, 1 - c]
        determinant_rows.append((1 - a) * (1 - c) - b**2)
        angle_rows.append(9 * ca.sum1((ja * sigma) ** 2) / np.radians(angle_deg) ** 2)
    nlp.constraints("position_band_diagonal", ca.vertcat(*diagonal_rows), 0.0, np.inf)
    nlp.constraints("position_band_determinant", ca.vertcat(*determinant_rows), 0.0, np.inf)
    nlp.constraints("angle_band", ca.vertcat(*angle_rows), -np.inf, 1.0)
    layout = nlp.build(-ca.sum1(y) / len(defaults))
    solution = Solver("tolerance_allocation", layout).solve({"log_tolerance": low},
                                                            failure="tolerance allocation did not converge")
    allocated = np.exp(solution["log_tolerance"])
    position, angle = statistical_bands(key_jacobian, allocated * sigma_per_tolerance)
    binding = ([f"pose_position_mm at {label}" for label, band in zip(labels, position, strict=True)
                if band >= position_mm * (1 - BINDING)]
               + [f"pose_angle_deg at {label}" for label, band in zip(labels, angle, strict=True)
                  if band >= angle_deg * (1 - BINDING)])
    return Allocation(allocated, position, angle, tuple(binding), solution.status, solution.iterations)

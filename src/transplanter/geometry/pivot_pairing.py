"""The other pivot of a dyad from one pivot, and a joint polish of both (eq 1 is bilinear).

Eq (1) for the pose pairs (1, i) is affine in the circle point for a known center and
affine in the center for a known circle point (``dyad_rows_in_circle``,
``dyad_rows_in_center``). All functions work on many dyads at once, in the local frame.
"""
from __future__ import annotations

import numpy as np

from transplanter._generated.burmester import dyad_rows_in_center, dyad_rows_in_circle
from transplanter.generated import numpy_twin

_rows_in_circle = numpy_twin(dyad_rows_in_circle)
_rows_in_center = numpy_twin(dyad_rows_in_center)


def _rows(twin, poses: np.ndarray, known: np.ndarray):
    """Stacked affine rows for pose pairs (1, 2..n): matrices (N, n-1, 2), constants (N, n-1)."""
    first = poses[0][:, None, None]
    others = poses[1:].T[:, :, None]
    coefficients, constant = twin(first, others, known.T[:, None, :])
    return np.moveaxis(coefficients, 0, -1).transpose(1, 0, 2), constant[0].T


def _solve(matrices, vectors):
    """Batched solve; pseudo-inverse fallback when some system is singular."""
    try:
        return np.linalg.solve(matrices, vectors[..., None])[..., 0]
    except np.linalg.LinAlgError:
        return np.einsum("nij,nj->ni", np.linalg.pinv(matrices), vectors)


def _least_squares(matrices, constants):
    """argmin |A x + b| per system, by normal equations (the polish restores full accuracy)."""
    transposed = matrices.transpose(0, 2, 1)
    return -_solve(transposed @ matrices, np.einsum("nji,nj->ni", matrices, constants))


def _minimum_norm(matrices, vectors):
    """Smallest x with A x = b per (wide or square) system."""
    return np.einsum("nji,nj->ni", matrices, _solve(matrices @ matrices.transpose(0, 2, 1), vectors))


def circles_for_centers(poses: np.ndarray, centers: np.ndarray) -> np.ndarray:
    """Circle points (N, 2) that best satisfy eq (1) for the given centers (N, 2)."""
    return _least_squares(*_rows(_rows_in_circle, poses, centers))


def centers_for_circles(poses: np.ndarray, circles: np.ndarray) -> np.ndarray:
    """Centers (N, 2) that best satisfy eq (1) for the given circle points (N, 2)."""
    return _least_squares(*_rows(_rows_in_center, poses, circles))


def polish(poses: np.ndarray, centers: np.ndarray, circles: np.ndarray, iterations: int = 3):
    """Gauss-Newton (minimum-norm steps) on eq (1) over both pivots; exact Jacobian from the rows."""
    for _ in range(iterations):
        in_circle, constants = _rows(_rows_in_circle, poses, centers)
        in_center, _ = _rows(_rows_in_center, poses, circles)
        residual = np.einsum("nij,nj->ni", in_circle, circles) + constants
        jacobian = np.concatenate([in_center, in_circle], axis=2)
        step = -_minimum_norm(jacobian, residual)
        centers, circles = centers + step[:, :2], circles + step[:, 2:]
    return centers, circles

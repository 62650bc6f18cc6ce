"""Burmester points of five poses: every real dyad, by elimination to one polynomial.

The center-point curves of poses (1, j, a, b) and (1, j, a, c) both pass through the pole
P1j. On the line P1j + t (1, tau) each meets the other curves in the roots of a quadratic;
a common root exists iff the degree-6 polynomial ``circular_cubic_pencil_resultant`` in
tau vanishes. Its real roots are the directions of the spurious common points (poles P1a,
Pja) and of the 0, 2 or 4 Burmester points; the spurious ones fail eq (1) for the fifth
pose and are dropped. Survivors are polished by Newton on the square system.
"""
from __future__ import annotations

import numpy as np

from transplanter._generated.burmester import (
    burmester_center_cubic,
    circular_cubic_pencil,
    circular_cubic_pencil_resultant,
)
from transplanter.generated import casadi_function
from transplanter.geometry.pivot_pairing import circles_for_centers, polish
from transplanter.geometry.poses import carry, pole


def pencil_pose_order(poses: np.ndarray) -> np.ndarray:
    """Pose 1 first, then the pose turned most against it (its pole is best conditioned)."""
    turn = 1 - np.cos(poses[1:, 2] - poses[0, 2])
    j = 1 + int(np.argmax(turn))
    return np.array([0, j, *[k for k in range(1, len(poses)) if k != j]])


def center_cubic(poses: np.ndarray) -> np.ndarray:
    cubic = casadi_function(burmester_center_cubic)
    return np.asarray(cubic(poses[:, 0], poses[:, 1], poses[:, 2])).ravel()


def _length_error(poses, centers, circles):
    """Largest change of the link length over the poses, per candidate (local units = pose scale)."""
    distances = np.linalg.norm(carry(poses, circles) - centers[:, None, :], axis=-1)
    return np.abs(distances - distances[:, :1]).max(axis=1)


def burmester_points(poses: np.ndarray, tolerance: float = 1e-10):
    """All real (center, circle) pairs of five local-frame poses; arrays (k, 2), k in {0, 2, 4}."""
    order = pencil_pose_order(poses)
    ordered = poses[order]
    pivot = pole(ordered[0], ordered[1])
    first = center_cubic(ordered[[0, 1, 2, 3]])
    second = center_cubic(ordered[[0, 1, 2, 4]])
    resultant = casadi_function(circular_cubic_pencil_resultant)
    polynomial = np.asarray(resultant(first, second, pivot)).ravel()
    taus = np.roots(polynomial / np.abs(polynomial).max())
    real = taus[np.abs(taus.imag) <= 1e-7 * (1 + np.abs(taus))].real
    directions = [np.array([1.0, tau]) / np.hypot(1.0, tau) for tau in real]
    if abs(polynomial[0]) <= 1e-12 * np.abs(polynomial).max():
        directions.append(np.array([0.0, 1.0]))  # a root at tau = infinity
    pencil = casadi_function(circular_cubic_pencil)
    candidates = []
    for direction in directions:
        alpha, beta, gamma = np.asarray(pencil(first, pivot, direction)).ravel()
        for t in np.roots([alpha, beta, gamma]):
            if abs(t.imag) <= 1e-7 * (1 + abs(t)):
                candidates.append(pivot + t.real * direction)
    if not candidates:
        return np.empty((0, 2)), np.empty((0, 2))
    centers = np.array(candidates)
    circles = circles_for_centers(poses, centers)
    keep = _length_error(poses, centers, circles) < 1e-5
    centers, circles = polish(poses, centers[keep], circles[keep], iterations=4)
    good = _length_error(poses, centers, circles) < tolerance
    return _distinct(centers[good], circles[good])


def _distinct(centers, circles, gap: float = 1e-7):
    kept: list[int] = []
    for k, g in enumerate(centers):
        if all(np.linalg.norm(g - centers[i]) > gap or np.linalg.norm(circles[k] - circles[i]) > gap for i in kept):
            kept.append(k)
    return centers[kept], circles[kept]

"""An RR dyad and its independent check against the poses it must guide."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.poses import carry, pose_scale, rotate_about


@dataclass(frozen=True)
class Link:
    """The dyad's ground when it is not the frame: a link turning about ``pivot`` by ``phases`` (rad, ccw)."""

    pivot: np.ndarray
    phases: np.ndarray


@dataclass(frozen=True)
class Dyad:
    """Fixed pivot ``center`` and moving pivot ``circle``, both where they are in pose 1 (mm).

    ``residuals_mm[i]`` is |M_i - G_i| - length at pose i, from forward kinematics.
    """

    center: np.ndarray
    circle: np.ndarray
    length: float
    residuals_mm: np.ndarray
    scale: float

    @property
    def max_residual_mm(self) -> float:
        return float(np.abs(self.residuals_mm).max())

    @property
    def max_residual(self) -> float:
        """Largest length error relative to the pose scale (dimensionless)."""
        return self.max_residual_mm / self.scale


def verify_dyads(poses: np.ndarray, centers, circles, link: Link | None = None) -> list[Dyad]:
    """Carry both pivots of each dyad through every pose by plain rigid motions and measure the link.

    This evaluation shares nothing with the synthesis algebra: it is the check of eq (1).
    ``centers`` and ``circles`` are (N, 2), where the pivots are in pose 1.
    """
    centers = np.asarray(centers, float).reshape(-1, 2)
    circles = np.asarray(circles, float).reshape(-1, 2)
    moving = carry(poses, circles)
    fixed = centers[:, None, :]
    if link is not None:
        fixed = rotate_about(fixed, link.pivot, link.phases - link.phases[0])
    distances = np.linalg.norm(moving - fixed, axis=-1)
    errors = distances - distances[:, :1]
    scale = pose_scale(poses)
    return [Dyad(c, m, float(d[0]), e, scale) for c, m, d, e in zip(centers, circles, distances, errors, strict=True)]


def verify_dyad(poses: np.ndarray, center, circle, link: Link | None = None) -> Dyad:
    """``verify_dyads`` for one dyad."""
    return verify_dyads(poses, center, circle, link)[0]

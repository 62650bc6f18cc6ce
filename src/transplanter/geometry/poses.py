"""Planar poses of a body as arrays of rows (x, y, angle): millimetres and radians.

A pose carries the body's reference point to (x, y) and turns the body by ``angle``
counterclockwise. Pose 1 (row 0) is the reference: circle points are given where the
moving pivot is in pose 1.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.planar import rotate


def rotation(angle):
    """2x2 rotation matrices, shape (..., 2, 2)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([np.stack([c, -s], -1), np.stack([s, c], -1)], -2)


def carry(poses: np.ndarray, point_in_first) -> np.ndarray:
    """Where body points, at ``point_in_first`` (..., 2) in pose 1, are in every pose: (..., n, 2)."""
    offset = np.asarray(point_in_first, float) - poses[0, :2]
    turned = np.einsum("nij,...j->...ni", rotation(poses[:, 2] - poses[0, 2]), offset)
    return poses[:, :2] + turned


def pole(first, second) -> np.ndarray:
    """Fixed point of the displacement from pose ``first`` to pose ``second`` (rotation needed)."""
    q = rotation(second[2] - first[2])
    return np.linalg.solve(np.eye(2) - q, second[:2] - q @ first[:2])


def rotate_about(points, pivot, angle) -> np.ndarray:
    """Points (..., 2) turned counterclockwise by ``angle`` (broadcast like points[..., 0]) about ``pivot``."""
    pivot = np.asarray(pivot, float)
    return pivot + rotate(angle, np.asarray(points, float) - pivot)


def relative_to_link(poses: np.ndarray, pivot, phases) -> np.ndarray:
    """Poses of the body seen from a link turning about ``pivot`` by ``phases`` (rad, ccw).

    The link frame coincides with the ground in pose 1, so pose 1 is unchanged and a
    link-fixed point keeps its pose-1 coordinates.
    """
    turn = -(np.asarray(phases, float) - phases[0])
    out = poses.copy()
    out[:, :2] = rotate_about(poses[:, :2], pivot, turn)
    out[:, 2] = poses[:, 2] + turn
    return out


@dataclass(frozen=True)
class Frame:
    """A similarity attached to the poses: origin at their centroid, unit length their size (``pose_scale``), x
    axis along the body's direction in the first pose. Seen in it, poses moved, turned or scaled together are the
    same poses, so every search, bound and start made there moves with them (and the numbers are conditioned)."""

    origin: np.ndarray
    scale: float
    angle: float = 0.0

    @classmethod
    def of(cls, poses: np.ndarray) -> Frame:
        origin = poses[:, :2].mean(axis=0)
        return cls(origin, pose_scale(poses), float(poses[0, 2]))

    def to_local(self, points) -> np.ndarray:
        return rotate(-self.angle, (np.asarray(points, float) - self.origin) / self.scale)

    def to_world(self, points) -> np.ndarray:
        return rotate(self.angle, points) * self.scale + self.origin

    def local_poses(self, poses: np.ndarray) -> np.ndarray:
        out = poses.copy()
        out[:, :2] = self.to_local(poses[:, :2])
        out[:, 2] = poses[:, 2] - self.angle
        return out


def pose_scale(poses: np.ndarray) -> float:
    """Largest distance of a pose position from their centroid (mm): the poses' own size, so a
    problem in micrometres or in metres is conditioned and judged as one in millimetres.

    Residuals are reported relative to it. When every pose sits on one point (the body only
    turns about it) there is no size, and 1 mm stands in.
    """
    spread = np.linalg.norm(poses[:, :2] - poses[:, :2].mean(axis=0), axis=1).max()
    return float(spread) if spread > 0 else 1.0

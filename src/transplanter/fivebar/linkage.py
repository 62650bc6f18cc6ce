"""The five-bar O-A-F-E-B of Wang et al. 2025 (Figure 8) by plain geometry: circle intersections only.

O is the origin. The carrier OA (length L1) stands at theta1 = carrier_angle - c after the
carrier has turned clockwise by c from pose 1. Connecting rod I (A-F, length L2) stands
at theta2 = theta1 + rho, rho being its angle relative to the carrier. The push plate is
rigid: E and F are fixed in its frame (origin P, x axis along the plate direction). The
receiving plate B-E (length L4) turns about the fixed hinge B. Nothing here uses the
derived closure: this is the independent forward evaluation.

A ``FiveBar`` may also hold a batch of mechanisms: every length and angle an array of one
batch shape, every point that shape plus (2,). The region keeps a trailing axis of one
(shape (K, 1)), so the methods broadcast the K mechanisms against a row of carrier turns.
Lengths are taken as sqrt(v . v) by matrix products, which round like ``np.linalg.norm``
of a single vector: a batch and a single mechanism give the same bits.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.planar import cross, unit
from transplanter.geometry.poses import rotation


def _angle(v):
    return np.arctan2(v[..., 1], v[..., 0])


def _length(v):
    """|v| over the last axis (2,)."""
    v = np.asarray(v, float)
    return np.sqrt((v[..., None, :] @ v[..., :, None])[..., 0, 0])


def _turn(matrix, v):
    """``matrix`` (2, 2) applied to points v (..., 2)."""
    return (matrix @ np.asarray(v, float)[..., None])[..., 0]


def circle_intersection(center, radius, through, other_radius, side):
    """Point X with |X - center| = radius and |X - through| = other_radius, on the ``side``
    (+1 or -1, sign of cross(through - center, X - center)). Returns (X, sin^2 of the angle at
    ``center``); where the circles miss, X is NaN and the second value negative."""
    offset = np.asarray(through, float) - center
    d = np.hypot(offset[..., 0], offset[..., 1])
    cos_angle = (d**2 + radius**2 - other_radius**2) / (2 * d * radius)
    margin = 1 - cos_angle**2
    sin_angle = np.sqrt(np.where(margin >= 0, margin, np.nan))
    u = offset / d[..., None]
    normal = np.stack([-u[..., 1], u[..., 0]], -1)
    point = center + np.asarray(radius)[..., None] * (cos_angle[..., None] * u + (side * sin_angle)[..., None] * normal)
    return point, margin


@dataclass(frozen=True)
class FiveBar:
    """Dimensions in mm and radians (one mechanism or a batch, see the module docstring);
    ``branch`` is the sign of cross(F - B, E - B) (assembly of B-E-F)."""

    carrier_length: float | np.ndarray
    carrier_angle: float | np.ndarray
    rod_length: float | np.ndarray
    hinge_b: np.ndarray
    receiving_length: float | np.ndarray
    e_local: np.ndarray
    f_local: np.ndarray
    branch: float | np.ndarray

    def __getitem__(self, index) -> FiveBar:
        """The mechanism(s) at ``index`` of a batch."""
        return FiveBar(*(value[index] for value in vars(self).values()))

    def as_batch(self) -> FiveBar:
        """One mechanism as a batch of one (fields (1, 1) and (1, 1, 2))."""
        return FiveBar(*(np.asarray(value, float)[None, None] for value in vars(self).values()))

    @property
    def link_length(self) -> float | np.ndarray:
        """L3 = |EF|, the push plate between its two hinges."""
        return _length(self.e_local - self.f_local)

    @property
    def ep(self) -> float | np.ndarray:
        return _length(self.e_local)

    @property
    def fp(self) -> float | np.ndarray:
        return _length(self.f_local)

    def carrier_point(self, c) -> np.ndarray:
        theta1 = self.carrier_angle - np.asarray(c, float)
        return np.asarray(self.carrier_length)[..., None] * unit(theta1)

    def plate_points(self, poses: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """E and F where the plate stands in ``poses`` (rows x, y, plate direction)."""
        turn = rotation(poses[..., 2])
        return (poses[..., :2] + np.einsum("...ij,...j->...i", turn, self.e_local),
                poses[..., :2] + np.einsum("...ij,...j->...i", turn, self.f_local))

    def relative_angle_at(self, poses: np.ndarray, c) -> np.ndarray:
        """rho = theta2 - theta1 that puts the plate in ``poses`` at carrier turns c (rad, in (-pi, pi])."""
        a = self.carrier_point(c)
        _, f = self.plate_points(poses)
        return np.angle(np.exp(1j * (_angle(f - a) - _angle(a))))

    def forward(self, c, rho) -> dict:
        """Plate pose and hinges for carrier turns c and relative angles rho (same shape)."""
        a = self.carrier_point(c)
        theta2 = self.carrier_angle - np.asarray(c, float) + rho
        f = a + np.asarray(self.rod_length)[..., None] * unit(theta2)
        e, margin = circle_intersection(self.hinge_b, self.receiving_length, f, self.link_length, self.branch)
        direction = _angle(f - e) - _angle(self.f_local - self.e_local)
        p = e - np.einsum("...ij,...j->...i", rotation(direction), self.e_local)
        return {"p": p, "direction": direction, "a": a, "f": f, "e": e, "margin": margin}

    def joint_chain_errors(self, poses: np.ndarray, c) -> tuple[np.ndarray, np.ndarray]:
        """With the plate placed exactly in ``poses``: |BE| - L4 and |AF| - L2 (mm)."""
        e, f = self.plate_points(poses)
        return (np.linalg.norm(e - self.hinge_b, axis=-1) - self.receiving_length,
                np.linalg.norm(f - self.carrier_point(c), axis=-1) - self.rod_length)


def assembly_branch(hinge_b, e, f) -> np.ndarray:
    """Sign of cross(F - B, E - B) for hinge positions E and F."""
    return np.sign(cross(np.asarray(f) - hinge_b, np.asarray(e) - hinge_b))


def from_hinges(pose1: np.ndarray, hinge_b, e1, a1, f1) -> FiveBar:
    """The five-bar whose hinges stand at B, E, A, F (mm, each (..., 2): a batch) in pose 1 (plate pose ``pose1``)."""
    hinge_b, e1, a1, f1 = (np.asarray(point, float) for point in (hinge_b, e1, a1, f1))
    back = rotation(-pose1[2])
    return FiveBar(carrier_length=np.hypot(a1[..., 0], a1[..., 1]), carrier_angle=_angle(a1),
                   rod_length=_length(f1 - a1), hinge_b=hinge_b, receiving_length=_length(e1 - hinge_b),
                   e_local=_turn(back, e1 - pose1[:2]), f_local=_turn(back, f1 - pose1[:2]),
                   branch=assembly_branch(hinge_b, e1, f1))

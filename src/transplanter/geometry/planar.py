"""Plane vectors, in numpy (x, y on the last axis, broadcasting) and as CasADi 2-element columns:
the unit vector at an angle, a counterclockwise rotation and the scalar cross product (radians); a
periodic value's remainder, cheaper than numpy's; a stand-in for the polar angle, cheaper than np.arctan2; and a
closed outline run counterclockwise."""
from __future__ import annotations

import casadi as ca
import numpy as np

#: One whole turn (rad).
TWO_PI = 2 * np.pi
#: One whole turn of ``diamond_angle``.
DIAMOND_TURN = 4.0


def modulo(value, period: float) -> np.ndarray:
    """``np.mod(value, period)`` (period > 0) as value - period floor(value / period), a few cheap operations where
    np.mod's floating remainder costs several times as much. The same value from -period to 2 period, to
    rounding beyond; within rounding of a multiple of the period it may give period, or a rounding error below
    0, for np.mod's 0 (or period)."""
    return value - period * np.floor(value / period)


def diamond_angle(x, y) -> np.ndarray:
    """A stand-in for the polar angle of the points (x, y) that increases with it, ``DIAMOND_TURN`` a turn:
    y / (|x| + |y|) where x >= 0 (-1 toward -y, 0 toward +x, 1 toward +y), 2 less that where x < 0 (3 toward -y).
    For what needs only the order of directions (an interpolation over them): a few cheap operations, where
    np.arctan2 takes tens of nanoseconds a point. NaN at the origin."""
    side = y / (np.abs(x) + np.abs(y))
    return np.where(x < 0, 2 - side, side)


def twice_signed_area(outline: np.ndarray) -> float:
    """Twice the area a closed outline (N, 2; its last point joined to its first, or a repeat of it) encloses,
    positive where it runs counterclockwise (the shoelace sum)."""
    x, y = outline[:, 0], outline[:, 1]
    return float(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))


def counterclockwise(outline: np.ndarray) -> np.ndarray:
    """The closed outline (N, 2) running counterclockwise (positive area): itself, or its points reversed."""
    return outline if twice_signed_area(outline) > 0 else outline[::-1]


def unit(angle) -> np.ndarray:
    """(cos, sin) of ``angle`` on a new last axis: shape angle.shape + (2,)."""
    return np.stack([np.cos(angle), np.sin(angle)], -1)


def rotate(angle, vectors) -> np.ndarray:
    """``vectors`` (..., 2) turned counterclockwise by ``angle`` (broadcast like vectors[..., 0])."""
    vectors = np.asarray(vectors, float)
    c, s = np.cos(angle), np.sin(angle)
    return np.stack([c * vectors[..., 0] - s * vectors[..., 1], s * vectors[..., 0] + c * vectors[..., 1]], -1)


def cross(u, v):
    """z component of u x v for vectors (..., 2): positive when v points counterclockwise of u."""
    return u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]


def casadi_unit(angle):
    """``unit`` for a CasADi scalar: the column (cos, sin)."""
    return ca.vertcat(ca.cos(angle), ca.sin(angle))


def casadi_rotate(angle, v):
    """``rotate`` for a CasADi 2-element column ``v``."""
    c, s = ca.cos(angle), ca.sin(angle)
    return ca.vertcat(c * v[0] - s * v[1], s * v[0] + c * v[1])


def casadi_cross(u, v):
    """``cross`` for CasADi 2-element columns."""
    return u[0] * v[1] - u[1] * v[0]

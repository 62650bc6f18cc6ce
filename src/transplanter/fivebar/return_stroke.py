"""Inverse kinematics of the return points (Wang et al. 2025 eq 3-4) with one consistent assembly.

A return point gives only where P is. E is where the circle of radius L4 about B meets
the circle of radius |EP| about P (two sides), which fixes the plate and so F; A is where
the carrier circle meets the circle of radius L2 about F (two sides). Of the 4 options per
point, the sequence kept is the one that (i) keeps the B-E-F assembly of the key poses
(the chain cannot change branch without jamming), (ii) has the carrier turn and the
relative angle both strictly increasing from the last key pose round to pose 1 plus a
turn, and (iii) turns the plate least (sum of squared plate-angle steps).

(ii) and (iii) only link consecutive points, so the best of the 4^m sequences is found
point by point (dynamic programming over the 4 options: 16 m comparisons, not 4^m), for a
whole batch of mechanisms at once.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.linkage import FiveBar, assembly_branch, circle_intersection
from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.poses import rotation

_SIDES = ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0))


@dataclass(frozen=True)
class ReturnStroke:
    """Carrier turns c_j, relative angles rho_j (unwrapped above rho1) and plate directions at the points.

    For a batch of K mechanisms each array is (K, m) and ``found`` (K,) says which have one.
    """

    carrier_turns: np.ndarray
    relative_angles: np.ndarray
    directions: np.ndarray
    found: np.ndarray | bool = True


def _options(mech: FiveBar, points: np.ndarray):
    """(c, rho, direction, valid) per mechanism, point and option: arrays (K, m, 4) of a batch (fields (K, 1))."""
    options = []
    for plate_side, carrier_side in _SIDES:
        e, _ = circle_intersection(mech.hinge_b, mech.receiving_length, points, mech.ep, plate_side)
        reach = e - points
        direction = np.arctan2(reach[..., 1], reach[..., 0]) - np.arctan2(mech.e_local[..., 1], mech.e_local[..., 0])
        f = points + np.einsum("...ij,...j->...i", rotation(direction), mech.f_local)
        a, _ = circle_intersection(np.zeros(2), mech.carrier_length, f, mech.rod_length, carrier_side)
        theta1 = np.arctan2(a[..., 1], a[..., 0])
        options.append((np.mod(mech.carrier_angle - theta1, TWO_PI),
                        np.arctan2((f - a)[..., 1], (f - a)[..., 0]) - theta1, direction,
                        np.where(assembly_branch(mech.hinge_b, e, f) == mech.branch, 1.0, np.nan)))
    return np.stack([np.stack(values, -1) for values in zip(*options, strict=True)])


def _steps(turn_from, rho_from, turn_to, rho_to):
    """Whether a step is allowed: carrier turn and relative angle both increase."""
    return (turn_to > turn_from) & (rho_to > rho_from)


def _squared_turn(direction_from, direction_to):
    return np.angle(np.exp(1j * (direction_to - direction_from)))**2


def solve_return_strokes(mech: FiveBar, points: np.ndarray, last_turn: float, rho1, last_rho,
                         last_direction: float) -> ReturnStroke:
    """The consistent option sequence of every mechanism of a batch (``mech`` fields (K, 1); ``rho1`` and
    ``last_rho`` (K,) rad; the plate's ``last_direction`` in the last key pose, rad); rows without one
    have ``found`` False."""
    c, rho, direction, valid = _options(mech, points)
    rho1, last_rho = (np.asarray(v, float)[:, None] for v in (rho1, last_rho))
    rho = rho1[..., None] + np.mod(rho - rho1[..., None], TWO_PI)
    usable = np.isfinite(valid) & np.isfinite(c)
    batch, m = c.shape[0], c.shape[1]
    cost = np.where(usable[:, 0] & _steps(last_turn, last_rho, c[:, 0], rho[:, 0]),
                    _squared_turn(last_direction, direction[:, 0]), np.inf)
    previous = np.zeros((batch, m, 4), int)
    for j in range(1, m):
        allowed = (usable[:, j - 1, :, None] & usable[:, j, None, :]
                   & _steps(c[:, j - 1, :, None], rho[:, j - 1, :, None], c[:, j, None, :], rho[:, j, None, :]))
        total = np.where(allowed, cost[:, :, None] + _squared_turn(direction[:, j - 1, :, None],
                                                                    direction[:, j, None, :]), np.inf)
        previous[:, j] = np.argmin(total, axis=1)
        cost = np.take_along_axis(total, previous[:, j, None, :], axis=1)[:, 0]
    cost = np.where(_steps(c[:, -1], rho[:, -1], TWO_PI, rho1 + TWO_PI), cost, np.inf)
    option = np.empty((batch, m), int)
    option[:, -1] = np.argmin(cost, axis=1)
    for j in range(m - 1, 0, -1):
        option[:, j - 1] = np.take_along_axis(previous[:, j], option[:, j, None], axis=1)[:, 0]
    chosen = [np.take_along_axis(values, option[..., None], axis=-1)[..., 0] for values in (c, rho, direction)]
    return ReturnStroke(chosen[0], chosen[1], chosen[2], found=np.isfinite(np.min(cost, axis=1)))


def solve_return_stroke(mech: FiveBar, points: np.ndarray, last_turn: float, rho1: float,
                        last_rho: float, last_direction: float) -> ReturnStroke | None:
    """The consistent option sequence of one mechanism, or None when no sequence meets (i) and (ii)."""
    stroke = solve_return_strokes(mech.as_batch(), points, last_turn, [rho1], [last_rho], last_direction)
    if not np.asarray(stroke.found)[0]:
        return None
    return ReturnStroke(stroke.carrier_turns[0], stroke.relative_angles[0], stroke.directions[0])

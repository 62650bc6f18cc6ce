"""Inverse kinematics of the return points (seed 000 eq 3-4) with one consistent assembly.

A return point gives only where P is. E is where the circle of radius L4 about B meets
the circle of radius |EP| about P (two sides), which fixes the plate and so F; A is where
the carrier circle meets the circle of radius L2 about F (two sides). Of the 4 options per
point, the sequence kept is the one that (i) keeps the B-E-F assembly of the key poses
(the chain cannot change branch without jamming), (ii) has the carrier turn and the
relative angle both strictly increasing from the last key pose round to pose 1 plus a
turn, and (iii) turns the plate least (sum of squared plate-angle steps).
"""
from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.linkage import FiveBar, assembly_branch, circle_intersection
from transplanter.geometry.poses import rotation

TWO_PI = 2 * np.pi
_SIDES = ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0))


@dataclass(frozen=True)
class ReturnStroke:
    """Carrier turns c_j, relative angles rho_j (unwrapped above rho1) and plate directions at the points."""

    carrier_turns: np.ndarray
    relative_angles: np.ndarray
    directions: np.ndarray


def _options(mech: FiveBar, points: np.ndarray):
    """(c, rho, direction, valid) per point and option: arrays (m, 4)."""
    out = np.full((4, len(points), 4), np.nan)
    for k, (plate_side, carrier_side) in enumerate(_SIDES):
        e, _ = circle_intersection(mech.hinge_b, mech.receiving_length, points, mech.ep, plate_side)
        direction = np.arctan2(*(e - points).T[::-1]) - np.arctan2(mech.e_local[1], mech.e_local[0])
        f = points + np.einsum("mij,j->mi", rotation(direction), mech.f_local)
        a, _ = circle_intersection(np.zeros(2), mech.carrier_length, f, mech.rod_length, carrier_side)
        theta1 = np.arctan2(a[:, 1], a[:, 0])
        out[0, :, k] = np.mod(mech.carrier_angle - theta1, TWO_PI)
        out[1, :, k] = np.arctan2((f - a)[:, 1], (f - a)[:, 0]) - theta1
        out[2, :, k] = direction
        out[3, :, k] = np.where(assembly_branch(mech.hinge_b, e, f) == mech.branch, 1.0, np.nan)
    return out


def solve_return_stroke(mech: FiveBar, points: np.ndarray, last_turn: float, rho1: float,
                        last_rho: float, last_direction: float) -> ReturnStroke | None:
    """The consistent option sequence, or None when no sequence meets (i) and (ii)."""
    c, rho, direction, valid = _options(mech, points)
    rho = rho1 + np.mod(rho - rho1, TWO_PI)
    m = len(points)
    combos = np.array(list(itertools.product(range(4), repeat=m)))
    pick = (np.arange(m), combos)
    cs = np.c_[np.full(len(combos), last_turn), c[pick], np.full(len(combos), TWO_PI)]
    rs = np.c_[np.full(len(combos), last_rho), rho[pick], np.full(len(combos), rho1 + TWO_PI)]
    ok = np.all(np.isfinite(valid[pick]) & np.isfinite(cs[:, 1:-1]), axis=1)
    ok &= np.all(np.diff(cs, axis=1) > 0, axis=1) & np.all(np.diff(rs, axis=1) > 0, axis=1)
    if not ok.any():
        return None
    turn = np.diff(np.c_[np.full(len(combos), last_direction), direction[pick]], axis=1)
    cost = np.where(ok, np.sum(np.angle(np.exp(1j * turn))**2, axis=1), np.inf)
    best = combos[int(np.argmin(cost))]
    chosen = (np.arange(m), best)
    return ReturnStroke(c[chosen], rho[chosen], direction[chosen])

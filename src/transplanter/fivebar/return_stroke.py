"""Inverse kinematics of the return points (Wang et al. 2025 eq 3-4): the passes of P by them, in order,
that a five-bar can make on one assembly.

A return point gives only where P is. E is where the circle of radius L4 about B meets the circle of
radius |EP| about P (two sides), which fixes the plate and so F; A is where the carrier circle meets the
circle of radius L2 about F (two sides). Each of the 4 options per point is a pass of P by it at some
carrier turn c and relative angle rho. A sequence of options, one per point, is consistent when (i) every
option keeps the B-E-F assembly of the key poses (the chain cannot change branch without jamming) and
(ii) the carrier turn and the relative angle both strictly increase from the last key pose through the
points round to pose 1 plus a turn. Its cost is how far the plate turns (sum of squared plate-angle
steps): the cheapest is the likeliest pass, but not always one a relative angle within the conditions
can follow, so the region tries them in order (``candidate.judge_candidates``).

(ii) and the cost link only consecutive points, so the cheapest completion from every option is found
point by point backwards (16 m comparisons, not 4^m), and the sequences are then grown forwards keeping,
per mechanism, the ``SEQUENCE_LIMIT`` partial sequences of cheapest completion: exactly the
``SEQUENCE_LIMIT`` cheapest consistent sequences, cheapest first, for a whole batch at once. A consistent
sequence without some of its points is consistent for the remaining points: a problem with a subset of
another's return points has every pass the other has.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.linkage import FiveBar, assembly_branch, circle_intersection
from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.poses import rotation

_SIDES = ((1.0, 1.0), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0))
#: Consistent sequences kept per mechanism, cheapest first.
SEQUENCE_LIMIT = 16


@dataclass(frozen=True)
class ReturnStroke:
    """Carrier turns c_j, relative angles rho_j (unwrapped above rho1) and plate directions at the points
    (arrays (m,); (S, m) for S sequences)."""

    carrier_turns: np.ndarray
    relative_angles: np.ndarray
    directions: np.ndarray


@dataclass(frozen=True)
class StrokeSequences:
    """The consistent sequences of a batch of mechanisms as rows, by mechanism and then cheapest first:
    ``owner`` (S,) the mechanism's row in the batch, ``stroke`` with arrays (S, m), ``cost`` (S,) rad^2."""

    owner: np.ndarray
    stroke: ReturnStroke
    cost: np.ndarray

    def rank(self) -> np.ndarray:
        """Each row's place among its mechanism's sequences (0: the cheapest)."""
        return _places(self.owner)


def _places(owner: np.ndarray) -> np.ndarray:
    """Each row's place in its run of equal ``owner`` values (rows sorted by owner)."""
    first = np.r_[0, np.flatnonzero(np.diff(owner)) + 1]
    return np.arange(len(owner)) - np.repeat(first, np.diff(np.r_[first, len(owner)]))


def _options(mech: FiveBar, points: np.ndarray) -> tuple[np.ndarray, ...]:
    """(c, rho, direction, valid) per mechanism, point and option: arrays (K, m, 4) of a batch (fields (K, 1));
    ``valid`` is 1 where the option exists on the mechanism's assembly branch, NaN elsewhere."""
    values = []
    for plate_side, carrier_side in _SIDES:
        e, _ = circle_intersection(mech.hinge_b, mech.receiving_length, points, mech.ep, plate_side)
        reach = e - points
        direction = np.arctan2(reach[..., 1], reach[..., 0]) - np.arctan2(mech.e_local[..., 1], mech.e_local[..., 0])
        f = points + np.einsum("...ij,...j->...i", rotation(direction), mech.f_local)
        a, _ = circle_intersection(np.zeros(2), mech.carrier_length, f, mech.rod_length, carrier_side)
        theta1 = np.arctan2(a[..., 1], a[..., 0])
        values.append((np.mod(mech.carrier_angle - theta1, TWO_PI),
                       np.arctan2((f - a)[..., 1], (f - a)[..., 0]) - theta1, direction,
                       np.where(assembly_branch(mech.hinge_b, e, f) == mech.branch, 1.0, np.nan)))
    return tuple(np.stack(group, -1) for group in zip(*values, strict=True))


def _steps(turn_from, rho_from, turn_to, rho_to):
    """Whether a step is allowed: carrier turn and relative angle both increase."""
    return (turn_to > turn_from) & (rho_to > rho_from)


def _squared_turn(direction_from, direction_to):
    return np.angle(np.exp(1j * (direction_to - direction_from)))**2


def stroke_sequences(mech: FiveBar, points: np.ndarray, last_turn: float, rho1, last_rho,
                     last_direction: float) -> StrokeSequences:
    """The ``SEQUENCE_LIMIT`` cheapest consistent sequences of every mechanism of a batch (``mech`` fields
    (K, 1); ``rho1`` and ``last_rho`` (K,) rad; the plate's ``last_direction`` in the last key pose, rad): a
    mechanism with none has no row."""
    c, rho, direction, valid = _options(mech, points)
    rho1, last_rho = (np.asarray(v, float)[:, None] for v in (rho1, last_rho))
    rho = rho1[..., None] + np.mod(rho - rho1[..., None], TWO_PI)
    usable = np.isfinite(valid) & np.isfinite(c)
    batch, m = c.shape[0], c.shape[1]

    to_go = np.where(usable[:, -1] & _steps(c[:, -1], rho[:, -1], TWO_PI, rho1 + TWO_PI), 0.0, np.inf)
    ahead = [to_go]
    for j in range(m - 1, 0, -1):
        allowed = (usable[:, j - 1, :, None] & usable[:, j, None, :]
                   & _steps(c[:, j - 1, :, None], rho[:, j - 1, :, None], c[:, j, None, :], rho[:, j, None, :]))
        step = _squared_turn(direction[:, j - 1, :, None], direction[:, j, None, :])
        to_go = np.min(np.where(allowed, step + to_go[:, None, :], np.inf), axis=2)
        ahead.insert(0, to_go)

    owner = np.repeat(np.arange(batch), 4)
    chosen = np.tile(np.arange(4), batch)[:, None]
    start = usable[:, 0] & _steps(last_turn, last_rho, c[:, 0], rho[:, 0])
    cost = np.where(start, _squared_turn(last_direction, direction[:, 0]), np.inf).ravel()
    owner, chosen, cost = _cheapest(owner, chosen, cost, ahead[0].ravel())
    for j in range(1, m):
        owner, last, cost = np.repeat(owner, 4), np.repeat(chosen[:, -1], 4), np.repeat(cost, 4)
        chosen = np.c_[np.repeat(chosen, 4, axis=0), np.tile(np.arange(4), len(chosen))]
        new = chosen[:, -1]
        allowed = usable[owner, j, new] & _steps(c[owner, j - 1, last], rho[owner, j - 1, last], c[owner, j, new],
                                                 rho[owner, j, new])
        cost = np.where(allowed, cost + _squared_turn(direction[owner, j - 1, last], direction[owner, j, new]), np.inf)
        owner, chosen, cost = _cheapest(owner, chosen, cost, ahead[j][owner, new])
    rows = (owner[:, None], np.arange(m), chosen)
    return StrokeSequences(owner, ReturnStroke(c[rows], rho[rows], direction[rows]), cost)


def _cheapest(owner, chosen, cost, to_go):
    """The rows whose sequence can be completed, the ``SEQUENCE_LIMIT`` of cheapest completion per owner,
    by owner and then by completion cost (ties in option order)."""
    total = cost + to_go
    order = np.lexsort((total, owner))
    order = order[np.isfinite(total[order])]
    kept = _places(owner[order]) < SEQUENCE_LIMIT
    return owner[order[kept]], chosen[order[kept]], cost[order[kept]]


def solve_return_stroke(mech: FiveBar, points: np.ndarray, last_turn: float, rho1: float, last_rho: float,
                        last_direction: float) -> ReturnStroke | None:
    """The cheapest consistent sequence of one mechanism, or None when it has none."""
    sequences = stroke_sequences(mech.as_batch(), points, last_turn, [rho1], [last_rho], last_direction)
    if not len(sequences.owner):
        return None
    stroke = sequences.stroke
    return ReturnStroke(stroke.carrier_turns[0], stroke.relative_angles[0], stroke.directions[0])

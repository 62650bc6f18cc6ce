"""The relative angles at which a five-bar closes with at least a closure margin: at each carrier turn c
a band rho_low(c) <= rho <= rho_high(c) of the connecting rod's angle relative to the carrier.

The margin sin^2(EBF) is at least m exactly where cos(BAF), the angle at A between AB and AF, lies in
[k_low, k_high] (derived: ``fivebar_closure_band``). F may stand on either side of the line AB; on the
side s (sign of cross(B - A, F - A)) the signed angle from AB to AF is delta = s BAF, and the margin holds
for BAF in [acos k_high, acos k_low]. Where k_high >= 1 the two sides meet at delta = 0 and the band runs
on across it to the other side (BAF down to -acos k_low), where k_low <= -1 they meet at pi (BAF up to
2 pi - acos k_high); elsewhere the sides are apart and a rod angle that keeps the margin stays on its
side. With theta1 = carrier_angle - c and psi the direction of AB, rho = psi - theta1 + delta.
"""
from __future__ import annotations

import numpy as np

from transplanter._generated.fivebar_closure_band import fivebar_closure_band
from transplanter.fivebar.linkage import FiveBar
from transplanter.generated import numpy_twin
from transplanter.geometry.planar import TWO_PI, cross


def rod_side(mech: FiveBar, turns: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """The side of line AB on which F stands (+1 left, -1 right) at carrier turns and relative angles."""
    state = mech.forward(turns, rho)
    return np.sign(cross(mech.hinge_b - state["a"], state["f"] - state["a"]))


def closure_band(mech: FiveBar, turns: np.ndarray, floor: float, side: float,
                 reference: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(rho_low, rho_high) at ``turns`` (rad) for one mechanism: where its closure margin is at least ``floor``
    with F on ``side`` of line AB, each band taken among its 2 pi shifts nearest ``reference`` (rad, a rough
    relative angle at the turns). NaN where no relative angle gives the margin."""
    a = mech.carrier_point(turns)
    frame = mech.hinge_b - a
    with np.errstate(invalid="ignore"):
        k_low, k_high = numpy_twin(fivebar_closure_band)(
            [mech.rod_length, mech.link_length, mech.receiving_length], np.hypot(frame[:, 0], frame[:, 1])[None],
            [floor])[0]
    empty = ~((k_low <= 1) & (k_high >= -1))       # also NaN: L3^2 < floor L4^2
    far, near = np.arccos(np.clip(k_low, -1, 1)), np.arccos(np.clip(k_high, -1, 1))
    lowest = np.where(k_high >= 1, -far, near)
    highest = np.where(k_low <= -1, TWO_PI - near, far)
    base = np.arctan2(frame[:, 1], frame[:, 0]) - mech.carrier_angle + turns
    low, high = (base + lowest, base + highest) if side > 0 else (base - highest, base - lowest)
    shift = TWO_PI * np.round((reference - (low + high) / 2) / TWO_PI)
    return np.where(empty, np.nan, low + shift), np.where(empty, np.nan, high + shift)

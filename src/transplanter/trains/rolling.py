"""Forward simulation of the planetary train from its four pitch curves alone.

Each gear is known only by its pitch curve in its own angle: the sun and the second
intermediate gear as designed (r = a / (1 + i)), the first intermediate gear and the
planet as the conjugates of their drivers (``conjugate_curve``: r2 = a - r1 at the angle
where the driver has turned int r1 / (a - r1)). Rolling without slip means equal arc
lengths run off both curves of a pair, so for a carrier turn c: the sun's arc s(c) gives
the first intermediate angle psi with S_1(psi) = s(c); the second intermediate gear (same
shaft) runs off S_2(psi), and the planet angle chi solves S_p(chi) = S_2(psi). The
contact gaps r_driver + r_driven - a measure how well the curves touch on the line of
centers. None of this uses the ratio that designed the curves.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.gears.pitch_curves import PitchCurve
from transplanter.geometry.turn_map import TurnMap
from transplanter.trains.planetary import PlanetaryTrain

#: Panels per turn of the rolling maps (0.25 deg): a train that uses its whole ratio range has
#: sharp stage-two curves, which 180 panels roll to only 1e-5 rad with 1e-4 mm contact gaps (720:
#: 2e-10 rad, 1e-9 mm; 1440: rounding, for 0.23 s instead of 0.07 s on the example).
ROLLING_PANELS = 1440


def conjugate_curve(driver: PitchCurve, center_distance: float) -> PitchCurve:
    """The driven pitch curve r2(psi) of an external pair, in the driven gear's own angle."""
    a = center_distance
    turn = TurnMap(lambda phi: (lambda r: r / (a - r))(driver.evaluate(phi)[0]), driver.breaks, ROLLING_PANELS)

    def evaluate(psi):
        phi = turn.inverse(psi)
        r, slope, bend = driver.evaluate(phi)
        w = (a - r) / r                     # dphi / dpsi
        w_phi = -a * slope / r**2
        return a - r, -slope * w, -(bend * w + slope * w_phi) * w

    return PitchCurve("conjugate", {"center_distance": a}, 1, evaluate, (), tuple(turn(np.asarray(driver.breaks))))


def arc_map(curve: PitchCurve) -> TurnMap:
    return TurnMap(lambda phi: np.hypot(*curve.evaluate(phi)[:2]), curve.breaks, ROLLING_PANELS)


@dataclass(frozen=True)
class Rolling:
    carrier_turns: np.ndarray
    relative_turn: np.ndarray      # chi = rho - rho1 (rad)
    contact_gaps_mm: tuple[np.ndarray, np.ndarray]


def roll_train(train: PlanetaryTrain, carrier_turns: np.ndarray) -> Rolling:
    a1, a2 = train.center_distances
    sun, second = train.sun, train.second_intermediate
    first, planet = conjugate_curve(sun, a1), conjugate_curve(second, a2)
    c = np.mod(carrier_turns, 2 * np.pi)
    psi = arc_map(first).inverse(arc_map(sun)(c))
    chi = arc_map(planet).inverse(arc_map(second)(psi))
    gaps = (sun.evaluate(c)[0] + first.evaluate(psi)[0] - a1, second.evaluate(psi)[0] + planet.evaluate(chi)[0] - a2)
    return Rolling(c, chi, gaps)

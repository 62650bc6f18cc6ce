"""Where the four pitch curves of the planetary train sit on the carrier, and how each turns with it.

Carrier frame: O at the origin, A on +x at the carrier length, the intermediate shaft at a1
from O and a2 from A (on the +y side for a bent carrier; on O-A when a1 + a2 = |OA|). Seen
from the carrier the fixed sun turns counterclockwise by the carrier turn c, the intermediate
shaft clockwise by psi(c), the planet (with rod I) counterclockwise by chi(c) = rho(c) - rho1.
The gear library draws a driver turning clockwise and its driven gear counterclockwise
(``GearPairDesign.points``), as stage 2 turns; stage 1 turns the other way, so its two curves
are mirrored (y -> -y) to be the parts as seen on the mechanism's plane. At c = 0 (pose 1)
every contact point lies on its line of centres.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.linkage import FiveBar
from transplanter.geometry.outline_thinning import DRAWN_WITHIN_MODULES, thinned
from transplanter.geometry.poses import rotate_about, rotation
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.trains.toothed_train import ToothedTrain, bend_angle

MIRROR = np.array([1.0, -1.0])


@dataclass(frozen=True)
class GearOnCarrier:
    """One gear: its pitch curve (M, 2) mm in its own frame, its centre (2,) mm in the carrier
    frame and its turn (rad, counterclockwise in the carrier frame) against the carrier turn c."""

    name: str
    role: str
    pitch_curve: np.ndarray
    center: np.ndarray
    angle: Callable[[np.ndarray], np.ndarray]
    mate_center: np.ndarray

    @property
    def contact_direction(self) -> float:
        """Direction (rad, in the gear's own frame) from its centre towards the contact point at pose 1."""
        towards = self.mate_center - self.center
        return float(np.arctan2(towards[1], towards[0]) - self.angle(np.zeros(1))[0])

    def placed(self, points: np.ndarray, c) -> np.ndarray:
        """Points (N, 2) of the gear's frame in the carrier frame at carrier turns c: (len(c), N, 2)."""
        turn = rotation(self.angle(np.atleast_1d(np.asarray(c, float))))
        return self.center + np.einsum("kij,nj->kni", turn, points)


def intermediate_shaft(train: PlanetaryTrain, carrier_length: float) -> np.ndarray:
    """Shaft centre (mm, carrier frame) at a1 from O and a2 from A, counterclockwise of O->A (on O-A when straight)."""
    a1, a2 = train.center_distances
    delta = bend_angle(a1, a2, carrier_length)
    return a1 * np.array([np.cos(delta), np.sin(delta)])


def gears_on_carrier(train: PlanetaryTrain, carrier_length: float) -> list[GearOnCarrier]:
    """Sun, first intermediate, second intermediate and planet, placed and turning by the designed motion."""
    shaft, planet = intermediate_shaft(train, carrier_length), np.array([carrier_length, 0.0])
    origin = np.zeros(2)
    to_shaft = np.arctan2(shaft[1], shaft[0])
    to_planet = np.arctan2(*(planet - shaft)[::-1])
    psi = train.intermediate_turn

    def chi(c):
        return train.relative_angle.evaluate(c) - train.relative_angle.evaluate(np.zeros(1))[0]

    one, two = train.stage_one.points, train.stage_two.points
    return [
        GearOnCarrier("sun", "driver, stage 1", one[0] * MIRROR, origin, lambda c: to_shaft + c, shaft),
        GearOnCarrier("first_intermediate", "driven, stage 1", one[1] * MIRROR, shaft, lambda c: to_shaft - psi(c),
                      origin),
        GearOnCarrier("second_intermediate", "driver, stage 2", two[0], shaft, lambda c: to_planet - psi(c), planet),
        GearOnCarrier("planet", "driven, stage 2", two[1], planet, lambda c: to_planet + chi(c), shaft),
    ]


def carrier_to_world(mech: FiveBar, points: np.ndarray, c) -> np.ndarray:
    """Carrier-frame points (..., 2) in the ground frame at carrier turn(s) c (the carrier at carrier_angle - c)."""
    return rotate_about(points, (0.0, 0.0), np.asarray(mech.carrier_angle - np.asarray(c, float))[..., None])


def cut_outlines(toothed: ToothedTrain) -> dict[str, np.ndarray]:
    """The cut outline (N, 2) mm of each gear of a toothed train, by the names of ``gears_on_carrier``
    (both place stage 1 mirrored and give each gear the same frame, so the outlines fit the pitch curves)."""
    return {gear.name.replace(" ", "_"): gear.outline for gear in toothed.gears}


def tooth_outlines(toothed: ToothedTrain) -> dict[str, np.ndarray]:
    """The cut outlines thinned within ``DRAWN_WITHIN_MODULES`` of the module for drawings and pictures: a
    shaper-cut outline has a vertex every 0.002 module, which drawings and frames do not need."""
    tolerance = DRAWN_WITHIN_MODULES * toothed.module
    return {name: thinned(outline, tolerance) for name, outline in cut_outlines(toothed).items()}


def teeth_on_carrier(toothed: ToothedTrain, carrier_length: float) -> dict:
    """Tooth outlines with their centres and turns on the carrier, as ``animation.Teeth`` takes them."""
    outlines = tooth_outlines(toothed)
    return {gear.name: (outlines[gear.name], gear.center, gear.angle)
            for gear in gears_on_carrier(toothed.train, carrier_length)}

"""Corners of the reverse train's pitch curves where the path touches a reach circle on a knot of its spline.

The elbow angle is the square root of the path's distance to the reach circle; where that distance's cubic
term jumps (the path's third derivative jumps at each knot of its cubic B-spline) the square root turns the
jump into one of chi'' (the rice example: +-0.0089 per rad at its nearest point). Every pitch curve's r' jumps
there with it: a corner, invisible to the curvature sampled on either side. For a curve r(phi) run
counterclockwise the tangent turns by the jump of mu = atan2(r, dr/dphi): a positive turn is a convex corner,
a negative one a hollow a rack cannot cut. The driven gear's curve is a - r1 at phi2, dr2/dphi2 = -r1' r2 / r1.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.reverse.arm_inverse import ArmMotion
from transplanter.trains.planetary import PlanetaryTrain

#: Offset (rad of the driver's turn) either side of a corner at which each side's slope is read (the curves
#: are piecewise polynomials broken at the touch, so this only has to stay clear of the break's own rounding).
SIDE = 1e-9
GEAR_NAMES = ("sun", "first intermediate", "second intermediate", "planet")
#: A tangent turn below this (rad) is the rounding of the slopes read either side, not a corner (the rice
#: example's outer touch, where the path is smooth: 3e-10 rad).
SMOOTH = 1e-6


@dataclass(frozen=True)
class PitchCorner:
    gear: str
    carrier_turn: float       # rad
    tangent_turn: float       # rad; negative: a hollow

    @property
    def hollow(self) -> bool:
        return self.tangent_turn < -SMOOTH

    @property
    def corner(self) -> bool:
        return abs(self.tangent_turn) > SMOOTH


def pitch_corners(motion: ArmMotion, train: PlanetaryTrain) -> list[PitchCorner]:
    """The tangent turn of each of the four pitch curves at every touch (zero where the path is smooth there)."""
    corners = []
    for touch in motion.touches:
        c = float(np.mod(motion.carrier_turn_at(np.array([touch.parameter]))[0], 2 * np.pi))
        for stage, driver_turn in ((train.stage_one, c), (train.stage_two, float(train.intermediate_turn(c)))):
            sides = np.mod(driver_turn + np.array([-SIDE, SIDE]), 2 * np.pi)
            r1, slope, _ = stage.driver.evaluate(sides)
            r2 = stage.center_distance - r1
            mu_driver = np.arctan2(r1, slope)
            mu_driven = np.arctan2(r2, -slope * r2 / r1)
            index = 0 if stage is train.stage_one else 2
            for k, mu in enumerate((mu_driver, mu_driven)):
                corners.append(PitchCorner(GEAR_NAMES[index + k], c, float(np.angle(np.exp(1j * (mu[1] - mu[0]))))))
    return corners

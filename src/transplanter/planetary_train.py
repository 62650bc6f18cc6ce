"""The planetary train of four non-circular gears that realises rho(c) (seed 000 eq 11-13).

Seen from the carrier, the fixed sun turns by c while the carrier turns clockwise by c;
the sun drives the first intermediate gear (stage 1, center distance a1), which shares
its shaft with the second intermediate gear, which drives the planet (stage 2, center
distance a2). Two external meshes keep the planet turning the sun's way, so the planet,
and with it connecting rod I, turns by rho(c) - rho1 relative to the carrier.

- Total ratio (eq 11): i0(c) = dc / drho = 1 / rho'(c).
- Split (eq 11-12): I1 = sqrt(i0); stage 1 must close (the intermediate gear turns once
  per sun turn): int_0^2pi dc / I1_corr = 2 pi with I1_corr = I1 / k, so
  k = 2 pi / int_0^2pi sqrt(rho') dc, and I2_corr = i0 / I1_corr = k I1. Stage 2 then closes by itself (the planet turns
  int rho' dc = 2 pi).
- Pitch curves (eq 13): r = a / (1 + i) for each stage's driver, the driven curve from
  the gear-pair library (``gear_pair.design_pair``), which checks closure, curvature and
  convexity. Stage 2's driver is a function of its own angle psi(c) = int_0^c dc / I1_corr.

Eq (12) as printed integrates 1/I1 over theta1 - theta2 (the rod's relative angle) instead
of the sun's angle; ``printed_correction`` evaluates that reading for comparison.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.gear_pair import GearPairDesign, design_pair
from transplanter.pitch_curves import PitchCurve, from_ratio
from transplanter.relative_angle import RelativeAngle
from transplanter.turn_map import TurnMap

TWO_PI = 2 * np.pi


@dataclass(frozen=True)
class PlanetaryTrain:
    relative_angle: RelativeAngle
    center_distances: tuple[float, float]
    correction: float                 # k of eq (12)
    stage_one: GearPairDesign         # sun -> first intermediate
    stage_two: GearPairDesign         # second intermediate -> planet
    intermediate_turn: TurnMap        # psi(c): first/second intermediate angle against the sun's

    @property
    def sun(self) -> PitchCurve:
        return self.stage_one.driver

    @property
    def second_intermediate(self) -> PitchCurve:
        return self.stage_two.driver


def _stage_one_ratio(relative: RelativeAngle):
    """I1 = rho'^(-1/2) and its first two derivatives in c."""

    def evaluate(c):
        s1, s2, s3 = (relative.evaluate(c, order) for order in (1, 2, 3))
        return s1**-0.5, -0.5 * s1**-1.5 * s2, 0.75 * s1**-2.5 * s2**2 - 0.5 * s1**-1.5 * s3

    return evaluate


def correction_factor(relative: RelativeAngle) -> float:
    """k of eq (12) over the sun's angle: 2 pi / int_0^2pi sqrt(rho'(c)) dc."""
    return TWO_PI / TurnMap(lambda c: np.sqrt(relative.evaluate(c, 1)), relative.knots).total


def printed_correction(relative: RelativeAngle) -> tuple[float, float]:
    """Eq (12) read as printed, integrating over the relative angle: k' = 2 pi / int sqrt(rho') drho,
    and how far (rad) the first intermediate gear then turns per sun turn (2 pi when it closes)."""
    k_printed = TWO_PI / TurnMap(lambda c: relative.evaluate(c, 1) ** 1.5, relative.knots).total
    turn = k_printed * TurnMap(lambda c: np.sqrt(relative.evaluate(c, 1)), relative.knots).total
    return k_printed, turn


def design_train(relative: RelativeAngle, center_distances: tuple[float, float], source: str = "<train>") -> PlanetaryTrain:
    slope = relative.evaluate(np.linspace(0, TWO_PI, 7200, endpoint=False), 1)
    if slope.min() <= 0:
        raise InfeasibleError(f"{source}: the relative angle is not strictly increasing (rho' reaches "
                              f"{slope.min():.4g}): the gears would have to reverse")
    a1, a2 = center_distances
    k = correction_factor(relative)
    stage_one_ratio = _stage_one_ratio(relative)
    sun = from_ratio(stage_one_ratio, 1 / k, a1, relative.knots)
    stage_one = design_pair(sun, 1, a1, source=source)
    psi = TurnMap(lambda c: k * np.sqrt(relative.evaluate(c, 1)), relative.knots)

    def stage_two_ratio(angle):
        c = psi.inverse(angle)
        i1, d1, dd1 = stage_one_ratio(c)
        return k * i1, i1 * d1, (dd1 * i1 + d1**2) * i1 / k

    second = from_ratio(stage_two_ratio, 1.0, a2, psi(relative.knots))
    stage_two = design_pair(second, 1, a2, source=source)
    return PlanetaryTrain(relative, (a1, a2), k, stage_one, stage_two, psi)

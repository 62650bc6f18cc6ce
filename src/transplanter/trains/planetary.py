"""The planetary train of four non-circular gears that realises rho(c) (Wang et al. 2025 eq 11-13).

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

- Peak-to-valley split (the reverse-gear-design paper's coefficient bs, here the exponent b in (0, 1)):
  I1 = i0^b / k and I2 = k i0^(1 - b), k = 2 pi / int rho'^b dc, so stage 1 carries the
  fraction b of the total ratio's logarithmic swing (b = 1/2 is the square root above).
  The reverse-gear-design paper prints i1 = i25 bs, i2 = i25 / i1, which leaves stage 2 at the constant 1 / bs
  and stage 1 closing only for bs = 1/n; ``printed_peak_to_valley_turn`` evaluates it.

Eq (12) as printed integrates 1/I1 over theta1 - theta2 (the rod's relative angle) instead
of the sun's angle; ``printed_correction`` evaluates that reading for comparison.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.gears.pair import GearPairDesign, design_pair
from transplanter.gears.pitch_curves import PitchCurve, from_ratio
from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.turn_map import TurnMap


class RelativeMotion(Protocol):
    """The planet's turn against the carrier as a function of the carrier's turn c (one turn each)."""

    @property
    def knots(self) -> np.ndarray: ...

    def evaluate(self, c, order: int = 0) -> np.ndarray: ...


@dataclass(frozen=True)
class PlanetaryTrain:
    relative_angle: RelativeMotion
    center_distances: tuple[float, float]
    correction: float                 # k of eq (12)
    stage_one: GearPairDesign         # sun -> first intermediate
    stage_two: GearPairDesign         # second intermediate -> planet
    intermediate_turn: TurnMap        # psi(c): first/second intermediate angle against the sun's
    exponent: float = 0.5             # stage one carries i0^exponent of the total ratio

    @property
    def sun(self) -> PitchCurve:
        return self.stage_one.driver

    @property
    def second_intermediate(self) -> PitchCurve:
        return self.stage_two.driver

    def stage_ratios(self, c) -> tuple[np.ndarray, np.ndarray]:
        """Corrected (I1, I2) at carrier turns c: I1 I2 = i0."""
        slope = self.relative_angle.evaluate(c, 1)
        return slope**-self.exponent / self.correction, self.correction * slope ** (self.exponent - 1)


def _power(relative: RelativeMotion, c, exponent: float):
    """(rho'^p, d/dc rho'^p, d2/dc2 rho'^p) at c."""
    s1, s2, s3 = (relative.evaluate(c, order) for order in (1, 2, 3))
    p = exponent
    return s1**p, p * s1 ** (p - 1) * s2, p * (p - 1) * s1 ** (p - 2) * s2**2 + p * s1 ** (p - 1) * s3


@dataclass(frozen=True)
class _Power:
    """rho'^p and its two c-derivatives as a ratio of the carrier turn c (the sun's, eq 11)."""

    relative: RelativeMotion
    exponent: float

    def __call__(self, c):
        return _power(self.relative, c, self.exponent)


@dataclass(frozen=True)
class _StageTwoRatio:
    """I2 = k rho'^(p - 1) and its two derivatives against the intermediate gear's angle psi(c)."""

    relative: RelativeMotion
    psi: TurnMap
    k: float
    exponent: float

    def __call__(self, angle):
        c = self.psi.inverse(angle)
        f, f_c, f_cc = (self.k * v for v in _power(self.relative, c, self.exponent - 1))
        psi_c, psi_cc, _ = (self.k * v for v in _power(self.relative, c, self.exponent))
        return f, f_c / psi_c, (f_cc * psi_c - f_c * psi_cc) / psi_c**3


def correction_factor(relative: RelativeMotion, exponent: float = 0.5) -> float:
    """k of eq (12) over the sun's angle: 2 pi / int_0^2pi rho'(c)^exponent dc."""
    return TWO_PI / TurnMap(lambda c: relative.evaluate(c, 1) ** exponent, relative.knots).total


def printed_correction(relative: RelativeMotion) -> tuple[float, float]:
    """Eq (12) read as printed, integrating over the relative angle: k' = 2 pi / int sqrt(rho') drho,
    and how far (rad) the first intermediate gear then turns per sun turn (2 pi when it closes)."""
    k_printed = TWO_PI / TurnMap(lambda c: relative.evaluate(c, 1) ** 1.5, relative.knots).total
    turn = k_printed * TurnMap(lambda c: np.sqrt(relative.evaluate(c, 1)), relative.knots).total
    return k_printed, turn


def printed_peak_to_valley_turn(relative: RelativeMotion, coefficient: float) -> float:
    """The reverse-gear-design paper's split as printed (I1 = i0 bs): the intermediate gear's turn
    per sun turn (2 pi closes)."""
    return TurnMap(lambda c: relative.evaluate(c, 1) / coefficient, relative.knots).total


def design_train(relative: RelativeMotion, center_distances: tuple[float, float], source: str = "<train>",
                 exponent: float = 0.5) -> PlanetaryTrain:
    """Two stages with I1 = i0^exponent / k and I2 = k i0^(1 - exponent) (exponent 1/2: eq 11-12)."""
    slope = relative.evaluate(np.linspace(0, TWO_PI, 7200, endpoint=False), 1)
    if slope.min() <= 0:
        raise InfeasibleError(f"{source}: the relative angle is not strictly increasing (rho' reaches "
                              f"{slope.min():.4g}): the gears would have to reverse; a train needs a motion "
                              "whose planet turns one way against the carrier all round")
    a1, a2 = center_distances
    k = correction_factor(relative, exponent)
    sun = from_ratio(_Power(relative, -exponent), 1 / k, a1, relative.knots)
    stage_one = design_pair(sun, 1, a1, source=source)
    psi = TurnMap(lambda c: k * relative.evaluate(c, 1) ** exponent, relative.knots)
    second = from_ratio(_StageTwoRatio(relative, psi, k, exponent), 1.0, a2, psi(relative.knots))
    stage_two = design_pair(second, 1, a2, source=source)
    return PlanetaryTrain(relative, (a1, a2), k, stage_one, stage_two, psi, exponent)

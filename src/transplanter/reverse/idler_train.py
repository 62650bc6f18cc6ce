"""Sun-idler-planet train with identical sun and planet, by the rice-transplanter paper's iteration (eq 5-12).

Seen from the carrier the sun turns by c, the idler by psi, the planet by chi (all one turn
per cycle, equal center distances L = s / 2 on a straight carrier). The rice-transplanter paper models the
planet as the sun's curve turned half a turn, r3(chi) = r1(chi + pi) (eq 8), so that with
i12 = (L - r1) / r1 (eq 6) and i23 = r3 / (L - r3) (eq 7) the total ratio i13 = i12 i23
(eq 5, 9; the generated ``idler_total_ratio``) involves r1 alone. The iteration (Figure 5):
r1 = L / (1 + i12); i23 from the shifted r1 at the planet's angle; i12 <- i13 / mean(i23,
i13 / i12); then the correction factor of eq (11-12), 1 / i12 <- 1 / i12 + x with
x = (2 pi - int dc / i12) / 2 pi, until i12 settles.

The train is then built as it would be made: the sun from the iterated r1, the idler as its
conjugate, the planet as the conjugate of the idler seen from the opposite side, and rolled
(``verify_idler_train``) with nothing else. In the real train the planet's contact radius at
sun angle c is r1(c*) with c* the sun angle half an idler turn away, not r1(chi + pi): the
two agree only for special paths (to first order about circular gears only the part of
ln i13 that changes sign under c -> c + pi can be produced), so the rolled tip shows how far
eq (8) is from the train it describes.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from transplanter._generated.planetary import idler_total_ratio
from transplanter.gears.pair import GearPairDesign, design_pair
from transplanter.gears.pitch_curves import PeriodicSpline, PitchCurve, Shifted, spline
from transplanter.generated import numpy_twin
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.arm_inverse import ArmMotion
from transplanter.reverse.verification import CHECK_POINTS, ReverseVerification, rebuild_tip
from transplanter.trains.planetary import RelativeMotion
from transplanter.trains.rolling import arc_map, conjugate_curve

_total_ratio = numpy_twin(idler_total_ratio)
#: Sun angles sampled by the iteration, iterations allowed, settling tolerance on i12, patience.
GRID, ITERATIONS, TOLERANCE, STALL = 1440, 500, 1e-12, 20


@dataclass(frozen=True)
class IdlerTrain:
    stage_one: GearPairDesign          # sun -> idler
    stage_two: GearPairDesign          # the idler's far side -> planet, same center distance
    planet: PitchCurve                 # conjugate of the idler's far side, in the planet's own angle
    iterations: int
    converged: bool
    model_residual: float              # max |i13 - i12 i23| under eq (8)'s model, relative
    correction: float                  # the last correction factor x of eq (12)

    @property
    def center_distance(self) -> float:
        return self.stage_one.center_distance


def seed_iteration(relative: RelativeMotion, center_distance: float):
    """The rice-transplanter paper's loop. Returns (c grid, r1, iterations run, settled, model residual, x) for the
    iterate whose eq (5) residual max |i12 i23 / i13 - 1| is smallest; the loop stops when i12
    settles or the residual has not improved for STALL iterations."""
    c = np.linspace(0, TWO_PI, GRID, endpoint=False)
    i13 = 1 / relative.evaluate(c, 1)
    planet_turn = np.mod(relative.evaluate(c, 0) + np.pi, TWO_PI)
    L = center_distance
    i12, x = np.ones_like(c), 0.0
    best, iterations = (np.inf, i12, x), 0
    for _ in range(ITERATIONS):
        iterations += 1
        r1 = L / (1 + i12)
        r3 = PeriodicSpline(c, r1).evaluate(planet_turn)[0]
        residual = float(np.abs(_total_ratio(np.array([r1, r3]), np.array([L]))[0][0] / i13 - 1).max())
        if residual < best[0]:
            best, stalled = (residual, i12, x), 0
        else:
            stalled += 1
        i23 = r3 / (L - r3)
        updated = i13 / ((i23 + i13 / i12) / 2)
        x = (TWO_PI - np.mean(1 / updated) * TWO_PI) / TWO_PI
        updated = 1 / (1 / updated + x)
        settled = np.abs(updated - i12).max() < TOLERANCE
        i12 = updated
        if settled or stalled >= STALL:
            break
    residual, i12, x = best
    return c, L / (1 + i12), iterations, bool(settled), residual, x


def _turned(curve: PitchCurve, angle: float) -> PitchCurve:
    """The same curve read from a direction ``angle`` further round."""
    return dataclasses.replace(curve, evaluator=Shifted(curve.evaluator, angle),
                               breaks=tuple(np.mod(np.asarray(curve.breaks) - angle, TWO_PI)))


def build_idler_train(sun: PitchCurve, source: str = "<train>") -> tuple[GearPairDesign, GearPairDesign, PitchCurve]:
    """The sun-idler pair at its closing center distance; the pair of the idler's far side and the
    planet at the same distance (checked to close by the gear-pair library); the planet curve."""
    stage_one = design_pair(sun, 1, None, source=source)
    far_side = _turned(conjugate_curve(sun, stage_one.center_distance), np.pi)
    stage_two = design_pair(far_side, 1, stage_one.center_distance, source=source)
    return stage_one, stage_two, conjugate_curve(far_side, stage_one.center_distance)


def design_idler_train(relative: RelativeMotion, center_distance: float, source: str = "<train>") -> IdlerTrain:
    c, r1, iterations, converged, residual, x = seed_iteration(relative, center_distance)
    return IdlerTrain(*build_idler_train(spline(c, r1), source), iterations, converged, residual, float(x))


def roll_idler_train(stage_one: GearPairDesign, planet: PitchCurve, carrier_turns: np.ndarray):
    """(chi, contact gaps): sun -> idler -> planet rolled by equal arc lengths from the curves alone."""
    a, sun = stage_one.center_distance, stage_one.driver
    idler = conjugate_curve(sun, a)
    far_side = _turned(idler, np.pi)
    psi = arc_map(idler).inverse(arc_map(sun)(carrier_turns))
    chi = arc_map(planet).inverse(arc_map(far_side)(psi))
    gaps = (sun.evaluate(carrier_turns)[0] + idler.evaluate(psi)[0] - a,
            far_side.evaluate(psi)[0] + planet.evaluate(chi)[0] - a)
    return chi, gaps


def verify_idler_train(motion: ArmMotion, train: IdlerTrain) -> ReverseVerification:
    c = np.linspace(0, TWO_PI, CHECK_POINTS, endpoint=False)
    chi, gaps = roll_idler_train(train.stage_one, train.planet, c)
    target = motion.trajectory.evaluate(motion.parameter_at(c))
    return ReverseVerification(c, target, rebuild_tip(motion, None, c, chi), gaps)

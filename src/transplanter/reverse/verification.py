"""Verification of a reverse design: roll the gears from their pitch curves alone, rebuild the tip.

``train_rolling.roll_train`` turns the carrier through a whole turn and returns how far the
planet has turned against it, using nothing but the four pitch curves. The tip is then
rebuilt by forward kinematics: for a straight carrier P = s e(theta) + l e(psi); for the
pick-up topology by the generated the cusp-pitch-curve paper eq (15) with the bent carrier (L1, L2, bend
delta0) and the arm's mounting alpha0 on the planet. The target is the path point where the
carrier has turned as far (the inverse kinematics' timing); the report gives the largest
distance between them.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.planetary import pickup_tip
from transplanter.generated import numpy_twin
from transplanter.reverse.arm_inverse import ArmMotion
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.trains.rolling import roll_train

_pickup_tip = numpy_twin(pickup_tip)
#: Carrier turns at which the rebuilt tip is compared (0.1 deg apart).
CHECK_POINTS = 3600


@dataclass(frozen=True)
class CarrierGeometry:
    """Where the planet sits on the carrier: O -> O1 (first) -> O2 (second), bent by ``bend``."""

    first: float
    second: float
    bend: float

    @property
    def offset(self) -> float:
        """Angle from O -> O1 to O -> O2."""
        return float(np.arctan2(self.second * np.sin(self.bend), self.first + self.second * np.cos(self.bend)))


@dataclass(frozen=True)
class ReverseVerification:
    carrier_turns: np.ndarray
    target: np.ndarray                 # (n, 2) path points at those carrier turns, mm (about the pivot)
    reproduced: np.ndarray             # (n, 2) tips rebuilt from the rolled gears
    contact_gaps_mm: tuple[np.ndarray, ...]

    @property
    def max_error_mm(self) -> float:
        return float(np.linalg.norm(self.reproduced - self.target, axis=1).max())


def rebuild_tip(motion: ArmMotion, geometry: CarrierGeometry | None, carrier_turns, planet_turns) -> np.ndarray:
    """Tip positions for carrier turns c and planet turns chi against the carrier (pivot frame)."""
    theta = motion.theta_grid[0] + motion.direction * carrier_turns
    gamma = motion.gamma_grid[0] - motion.direction * planet_turns
    if geometry is None:
        carrier_length, arm_length = motion.carrier_length, motion.arm_length
        return np.c_[carrier_length * np.cos(theta) + arm_length * np.cos(theta + gamma),
                     carrier_length * np.sin(theta) + arm_length * np.sin(theta + gamma)]
    first_segment = theta - geometry.offset
    mounting = motion.gamma_grid[0] + geometry.offset - geometry.bend
    angles = np.array([first_segment, np.full_like(theta, geometry.bend), gamma - motion.gamma_grid[0],
                       np.full_like(theta, mounting)])
    lengths = np.array([geometry.first, geometry.second, motion.arm_length])[:, None]
    return _pickup_tip(lengths, angles)[0].T


def verify_reverse(motion: ArmMotion, train: PlanetaryTrain, geometry: CarrierGeometry | None) -> ReverseVerification:
    c = np.linspace(0, 2 * np.pi, CHECK_POINTS, endpoint=False)
    rolling = roll_train(train, c)
    target = motion.trajectory.evaluate(motion.parameter_at(c))
    return ReverseVerification(c, target, rebuild_tip(motion, geometry, c, rolling.relative_turn),
                               rolling.contact_gaps_mm)

"""Independent check of a designed five-bar: the gears roll, then the linkage closes.

The planet's turn comes from ``train_rolling`` (pitch curves only), the plate from
``FiveBar.forward`` (circle intersections only). Reported: P and plate-angle errors at the
key poses, the distance of the return points from the reached ones, the largest gap
between the trajectory the gears make and the one the spline asks for, the contact gaps,
and the whole-turn conditions (closure margin, eq 10 discriminant, monotonic rho).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.generated import numpy_twin
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.fivebar.relative_angle import RelativeAngle, ratio_range
from transplanter.trains.rolling import roll_train

TWO_PI = 2 * np.pi
#: Carrier turns of the whole-turn check (0.1 deg apart).
TURN_SAMPLES = 3600

_discriminant = numpy_twin("fivebar", "fivebar_discriminant")


@dataclass(frozen=True)
class Verification:
    carrier_turns: np.ndarray        # whole-turn grid (rad)
    trajectory: np.ndarray           # P over the grid, from the rolling gears (mm)
    directions: np.ndarray           # plate direction over the grid (rad)
    key_position_errors_mm: np.ndarray
    key_angle_errors_deg: np.ndarray
    return_point_errors_mm: np.ndarray
    roundtrip_max_error_mm: float
    contact_gap_mm: float
    min_closure_margin: float
    min_discriminant: float
    min_slope: float
    ratio_range: tuple[float, float]

    @property
    def relative_angle_monotonic(self) -> bool:
        return self.min_slope > 0


def discriminant(mech: FiveBar, carrier_turns: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """Eq (10), B^2 - 4AC (mm^4), from the generated derivation."""
    theta1 = mech.carrier_angle - carrier_turns
    b = mech.hinge_b
    lengths = [mech.carrier_length, mech.rod_length, mech.link_length, mech.receiving_length, np.hypot(*b)]
    angles = [theta1, theta1 + rho, np.full_like(theta1, np.arctan2(b[1], -b[0]))]
    return _discriminant(lengths, angles)[0]


def verify(problem: FiveBarProblem, mech: FiveBar, relative: RelativeAngle, train: PlanetaryTrain,
           return_turns: np.ndarray) -> Verification:
    grid = np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)
    turns = np.r_[problem.carrier_turns, return_turns, grid]
    rolling = roll_train(train, turns)
    rho = relative.rho1 + rolling.relative_turn
    state = mech.forward(turns, rho)
    wanted = mech.forward(turns, relative.evaluate(turns))
    k, m = len(problem.carrier_turns), len(return_turns)
    key_p, key_direction = state["p"][:k], state["direction"][:k]
    slope = relative.evaluate(grid, 1)
    whole = slice(k + m, None)
    return Verification(
        carrier_turns=grid, trajectory=state["p"][whole], directions=state["direction"][whole],
        key_position_errors_mm=np.linalg.norm(key_p - problem.poses[:, :2], axis=1),
        key_angle_errors_deg=np.degrees(np.angle(np.exp(1j * (key_direction - problem.poses[:, 2])))),
        return_point_errors_mm=np.linalg.norm(state["p"][k:k + m] - problem.return_points, axis=1),
        roundtrip_max_error_mm=float(np.nanmax(np.linalg.norm(state["p"] - wanted["p"], axis=1))),
        contact_gap_mm=float(max(np.abs(g).max() for g in rolling.contact_gaps_mm)),
        min_closure_margin=float(np.min(state["margin"][whole])),
        min_discriminant=float(np.min(discriminant(mech, grid, rho[whole]))),
        min_slope=float(slope.min()),
        ratio_range=ratio_range(slope))

"""Independent check of a designed five-bar: the gears roll, then the linkage closes.

The planet's turn comes from ``train_rolling`` (pitch curves only), the plate from
``loop_closure.close_loop`` (the derived loop equation eq 8-9 solved by Newton), so neither the
spline that designed the gears nor the synthesis's circle intersections (``FiveBar.forward``) are
reused. Reported: P and plate-angle errors at the key poses, the distance of the return points
from the reached ones, the largest gap between the trajectory the gears make and the one the
spline asks for, the contact gaps, and the whole-turn conditions (closure margin, eq 10
discriminant, monotonic rho). ``failures`` names every check that misses its tolerance.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.fivebar import fivebar_discriminant
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.loop_closure import close_loop
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, ratio_range
from transplanter.generated import numpy_twin
from transplanter.geometry.planar import TWO_PI
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.trains.rolling import roll_train

#: Carrier turns of the whole-turn check (0.1 deg apart).
TURN_SAMPLES = 3600
#: Key-pose, round-trip and contact tolerance per mm of the mechanism's reach (largest |OP| at the key
#: poses), and the plate-angle tolerance in rad: about 1e-6 mm on the 315 mm reach of the bundled example.
RELATIVE_TOLERANCE = 3e-9
#: Relative slack on the closure-margin floor, which the NLP meets on its grid, checked here on a finer one.
MARGIN_FLOOR_SLACK = 1e-6

_discriminant = numpy_twin(fivebar_discriminant)


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
    tolerance_mm: float              # key poses, round trip, contact gaps (mm); plate angle: tolerance_mm / reach (rad)
    failures: tuple[str, ...]        # every check that missed, with its numbers; empty when all pass

    @property
    def relative_angle_monotonic(self) -> bool:
        return self.min_slope > 0

    @property
    def passed(self) -> bool:
        return not self.failures


def discriminant(mech: FiveBar, carrier_turns: np.ndarray, rho: np.ndarray) -> np.ndarray:
    """Eq (10), B^2 - 4AC (mm^4), from the generated derivation."""
    theta1 = mech.carrier_angle - carrier_turns
    b = mech.hinge_b
    lengths = [mech.carrier_length, mech.rod_length, mech.link_length, mech.receiving_length, np.hypot(*b)]
    angles = [theta1, theta1 + rho, np.full_like(theta1, np.arctan2(b[1], -b[0]))]
    return _discriminant(lengths, angles)[0]


def _failures(problem: FiveBarProblem, check: dict, tolerance_mm: float, reach: float) -> tuple[str, ...]:
    failed = []
    for k, label in enumerate(problem.labels):
        position, angle = check["key_position_errors_mm"][k], check["key_angle_errors_deg"][k]
        if not position <= tolerance_mm:
            failed.append(f"key pose {label}: P misses by {position:.3g} mm (tolerance {tolerance_mm:.2g} mm)")
        if not abs(angle) <= np.degrees(tolerance_mm / reach):
            failed.append(f"key pose {label}: plate angle off by {angle:.3g} deg "
                          f"(tolerance {np.degrees(tolerance_mm / reach):.2g} deg)")
    if not check["min_closure_margin"] >= problem.min_closure_margin * (1 - MARGIN_FLOOR_SLACK):
        failed.append(f"closure margin sin^2(EBF) falls to {check['min_closure_margin']:.4g} over the turn "
                      f"(required {problem.min_closure_margin:g}; negative or NaN: the chain does not close)")
    if not check["min_slope"] > 0:
        failed.append(f"relative angle not increasing: rho' reaches {check['min_slope']:.4g}")
    for name in ("roundtrip_max_error_mm", "contact_gap_mm"):
        if not check[name] <= tolerance_mm:
            failed.append(f"{name.removesuffix('_mm').replace('_', ' ')} {check[name]:.3g} mm "
                          f"(tolerance {tolerance_mm:.2g} mm)")
    return tuple(failed)


def verify(problem: FiveBarProblem, mech: FiveBar, relative: RelativeAngle, train: PlanetaryTrain,
           return_turns: np.ndarray) -> Verification:
    grid = np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)
    turns = np.r_[problem.carrier_turns, return_turns, grid]
    rolling = roll_train(train, turns)
    rho = relative.rho1 + rolling.relative_turn
    state = close_loop(mech, turns, rho)
    wanted = close_loop(mech, turns, relative.evaluate(turns))
    k, m = len(problem.carrier_turns), len(return_turns)
    key_p, key_direction = state["p"][:k], state["direction"][:k]
    slope = relative.evaluate(grid, 1)
    whole = slice(k + m, None)
    reach = float(np.linalg.norm(problem.poses[:, :2], axis=1).max())
    check = {
        "key_position_errors_mm": np.linalg.norm(key_p - problem.poses[:, :2], axis=1),
        "key_angle_errors_deg": np.degrees(np.angle(np.exp(1j * (key_direction - problem.poses[:, 2])))),
        "return_point_errors_mm": np.linalg.norm(state["p"][k:k + m] - problem.return_points, axis=1),
        "roundtrip_max_error_mm": float(np.max(np.linalg.norm(state["p"] - wanted["p"], axis=1))),
        "contact_gap_mm": float(max(np.abs(g).max() for g in rolling.contact_gaps_mm)),
        "min_closure_margin": float(np.min(state["margin"][whole])),
        "min_slope": float(slope.min()),
    }
    return Verification(
        carrier_turns=grid, trajectory=state["p"][whole], directions=state["direction"][whole],
        min_discriminant=float(np.min(discriminant(mech, grid, rho[whole]))), ratio_range=ratio_range(slope),
        tolerance_mm=RELATIVE_TOLERANCE * reach, failures=_failures(problem, check, RELATIVE_TOLERANCE * reach, reach),
        **check)

"""Forward kinematics of the pick-up mechanism (the cusp-pitch-curve paper, section 6.1, eq 15).

Stage 1: the fixed sun (gear 1) at O meshes with gear 2 at O1; stage 2: gear 3, fixed to gear 2,
meshes with the planet (gear 4) at O2, which carries the arm. Each stage's pitch curve is scaled
so that its pair closes (one driven turn per driver turn) at its carrier length, L1 and L2.

Seen from the carrier, turned counterclockwise by c, the sun turns clockwise by c: the pair
convention of ``gears.pair`` (driver clockwise by phi1, contact at its polar angle phi1, driven
counterclockwise by phi2(phi1)). Gear 2, and gear 3 with it, turns counterclockwise by
chi = phi2_1(c). Gear 3 turning counterclockwise is the mirror image of the convention, so stage 2
is designed on gear 3's mirrored curve r3(-theta), and the planet turns clockwise by
phi2_2(chi): its turn against the carrier is psi(c) = -phi2_2(phi2_1(c)). Eq (15) then places the
tip (``planetary.pickup_tip``): Q = L1 e(phi0 + c) + L2 e(phi0 + c + delta0) + S e(phi0 + c + delta0
+ psi + alpha0), phi0 + c being the paper's phi0 + phi1 and psi its phi2 (docs/reverse.md on the
Table 1 labels). The tip velocity is dQ/dt = omega (dQ/dc), with dpsi/dc = -(r1 / (L1 - r1))
(r3 / (L2 - r3)) at the contact radii (pure rolling, derivations/gears.py), and the angle
derivatives of Q from casadi's automatic differentiation of the generated eq (15).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter._generated.planetary import pickup_tip
from transplanter.api_arguments import require_problem
from transplanter.errors import InfeasibleError
from transplanter.gears.pair import GearPairDesign, design_pair, driven_angle
from transplanter.gears.pitch_curves import PitchCurve
from transplanter.generated import casadi_function
from transplanter.geometry.planar import TWO_PI
from transplanter.pickup.problem import PickupProblem
from transplanter.pickup.result import PickupResult

#: Carrier positions per turn.
SAMPLES = 1440


def mirrored(curve: PitchCurve) -> PitchCurve:
    """The curve reflected in its own x axis, r(-theta): what a gear turning counterclockwise shows a pair
    designed for a clockwise driver."""
    flip = tuple(float(np.mod(-b, TWO_PI)) for b in curve.breaks)
    return PitchCurve(curve.family, curve.parameters, curve.lobes, _Mirrored(curve), flip, flip)


@dataclass(frozen=True)
class _Mirrored:
    """r(-theta) with its slope and bend (``mirrored``)."""

    curve: PitchCurve

    def __call__(self, phi: np.ndarray) -> tuple:
        r, slope, bend = self.curve.evaluate(np.mod(-phi, TWO_PI))
        return r, -slope, bend


def stage_at(curve: PitchCurve, center_distance: float, source: str, name: str) -> GearPairDesign:
    """The pair of ``curve`` scaled to close (driven turn 2 pi per driver turn) at ``center_distance``."""
    if curve.lobes != 1:
        raise InfeasibleError(f"{source}: {name}.driver has order {curve.lobes}: the pick-up train needs one turn "
                              f"of every gear per carrier turn (order 1)")
    natural = design_pair(curve, 1, source=source, where=f"{name}.driver").center_distance
    return design_pair(curve.scaled(center_distance / natural), 1, source=source, where=f"{name}.driver")


def _tip_and_rates():
    """Q and dQ/d(angles) as one casadi Function of the generated eq (15)."""
    tip = casadi_function(pickup_tip)
    lengths, angles = ca.SX.sym("lengths", 3), ca.SX.sym("angles", 4)
    q = tip(lengths, angles)
    return ca.Function("pickup_tip_rates", [lengths, angles], [q, ca.jacobian(q, angles)])


def synthesize(problem: PickupProblem) -> PickupResult:
    """Tip path, picking and pushing angles and tip speed over one carrier turn (module docstring)."""
    require_problem(problem, PickupProblem, "pickup")
    start = time.perf_counter()
    first = stage_at(problem.stages[0], problem.first_length, problem.source, "stage1")
    second = stage_at(mirrored(problem.stages[1]), problem.second_length, problem.source, "stage2")
    c = np.linspace(0.0, TWO_PI, SAMPLES, endpoint=False)
    chi = driven_angle(first, c)
    psi = -driven_angle(second, chi)
    r1 = np.interp(c, first.phi1, first.radius[0])
    r3 = np.interp(np.mod(chi, TWO_PI), second.phi1, second.radius[0])
    dpsi = -(r1 / (problem.first_length - r1)) * (r3 / (problem.second_length - r3))
    angles = np.array([problem.start + c, np.full_like(c, problem.bend), psi, np.full_like(c, problem.mounting)])
    lengths = np.array([problem.first_length, problem.second_length, problem.arm_length])
    rates = _tip_and_rates().map(len(c))
    q, jacobian = rates(np.tile(lengths[:, None], len(c)), angles)
    tip = np.asarray(q).T
    jac = np.asarray(jacobian)                                    # (2, 4 N): sample k in columns 4k .. 4k + 3
    velocity = problem.speed * (jac[:, 0::4] + jac[:, 2::4] * dpsi)   # dQ/dc = dQ/d(carrier) + dQ/dpsi dpsi/dc
    whole = float(-driven_angle(second, driven_angle(first, np.array([TWO_PI])))[0])
    return PickupResult(problem, first, second, c, psi, tip, velocity.T, dpsi, whole,
                        {"kinematics": time.perf_counter() - start})

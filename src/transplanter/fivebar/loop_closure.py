"""The five-bar closed through its derived loop equation (Wang et al. 2025 eq 8-10), not by circle intersection.

For a carrier turn c and a relative angle rho, theta1 = carrier_angle - c, theta2 = theta1 + rho and
theta5 = atan2(B_y, -B_x) (the frame convention of ``derivations/fivebar.py``). The receiving plate's
angle theta4 is a root of eq (8), f(theta4) = |OA + AF - OB - BE|^2 - L3^2 (generated
``fivebar_closure``). The start is the root of eq (9)'s quadratic in t = tan(theta4 / 2) whose E
lies on the design's assembly branch, written theta4 = 2 atan2(-B +- sqrt(B^2 - 4AC), 2A) so that
A = 0 (theta4 = pi) needs no special case; Newton on eq (8), with casadi's derivative, then
takes it to rounding level. E = B + L4 e(theta4) and F = A + L2 e(theta2) carry the rigid plate, and
with it P. Where eq (10) is negative the chain does not close: E, P and the plate angle are NaN.

``FiveBar.forward`` (the synthesis's own route) is not used: this is the verification's route.
"""
from __future__ import annotations

import functools

import casadi as ca
import numpy as np

from transplanter._generated.fivebar import fivebar_closure, fivebar_closure_margin, fivebar_half_angle_quadratic
from transplanter.fivebar.linkage import FiveBar, assembly_branch
from transplanter.generated import casadi_function, numpy_twin
from transplanter.geometry.planar import unit
from transplanter.geometry.poses import rotation

#: Newton steps after the eq (9) start (two suffice at rounding level; the rest guard a poor start).
NEWTON_STEPS = 6

_half_angle_quadratic = numpy_twin(fivebar_half_angle_quadratic)
_closure_margin = numpy_twin(fivebar_closure_margin)


@functools.cache
def _closure_and_slope() -> ca.Function:
    """Eq (8) residual (mm^2) and its derivative in theta4 (mm^2/rad), by casadi's AD."""
    closure = casadi_function(fivebar_closure)
    lengths, angles = ca.SX.sym("lengths", 5), ca.SX.sym("angles", 4)
    residual = closure(lengths, angles)
    return ca.Function("closure_and_slope", [lengths, angles], [residual, ca.jacobian(residual, angles[2])])


def close_loop(mech: FiveBar, carrier_turns, rho) -> dict:
    """Hinges and plate of one mechanism for carrier turns c and relative angles rho (1-D, same length, rad).

    Returns
    -------
    dict
        ``p`` (n, 2) mm, ``direction`` (n,) rad (plate direction, counterclockwise from +x), ``a``, ``e``,
        ``f`` (n, 2) mm, ``theta4`` (n,) rad, ``margin`` (n,) sin^2 of the angle EBF from eq (10) (negative
        where the chain does not close) and ``residual`` (n,) |eq (8)| / L3^2 after Newton.
    """
    c, rho = np.atleast_1d(np.asarray(carrier_turns, float)), np.atleast_1d(np.asarray(rho, float))
    theta1 = mech.carrier_angle - c
    theta2 = theta1 + rho
    b = np.asarray(mech.hinge_b, float)
    lengths = np.array([mech.carrier_length, mech.rod_length, mech.link_length, mech.receiving_length,
                        np.hypot(*b)], float)
    crank = np.array([theta1, theta2, np.full_like(c, np.arctan2(b[1], -b[0]))])
    margin = _closure_margin(lengths, crank)[0][0]
    closes = margin >= 0
    a = mech.carrier_length * unit(theta1)
    f = a + mech.rod_length * unit(theta2)

    quadratic_a, quadratic_b, quadratic_c = _half_angle_quadratic(lengths, crank)[0]
    root = np.sqrt(np.where(closes, quadratic_b**2 - 4 * quadratic_a * quadratic_c, np.nan))
    roots = 2 * np.arctan2(-quadratic_b[None] + np.array([[1.0], [-1.0]]) * root, 2 * quadratic_a[None])
    on_branch = assembly_branch(b, b + mech.receiving_length * unit(roots), f) == mech.branch
    theta4 = np.where(on_branch[0], roots[0], roots[1])

    step_function = _closure_and_slope().map(len(c))
    angles = np.vstack([theta1, theta2, theta4, crank[2]])
    for _ in range(NEWTON_STEPS):
        value, slope = (np.asarray(v).ravel() for v in step_function(np.repeat(lengths[:, None], len(c), 1), angles))
        angles[2] -= np.where(closes & (slope != 0), value / np.where(slope != 0, slope, 1.0), 0.0)
    residual = np.asarray(step_function(np.repeat(lengths[:, None], len(c), 1), angles)[0]).ravel()

    theta4 = np.where(closes, angles[2], np.nan)
    e = b + mech.receiving_length * unit(theta4)
    plate_axis = np.asarray(mech.f_local) - mech.e_local
    direction = np.arctan2(*(f - e).T[::-1]) - np.arctan2(plate_axis[1], plate_axis[0])
    p = e - np.einsum("...ij,j->...i", rotation(direction), mech.e_local)
    return {"p": p, "direction": direction, "a": a, "e": e, "f": f, "theta4": theta4, "margin": margin,
            "residual": np.abs(residual) / mech.link_length**2}

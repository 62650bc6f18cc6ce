"""Kinetostatics of the five-bar O-A-F-E-B (Wang et al. 2025 Figure 8): the loop at velocity level and the force
at its cut E.

Model: quasi-static (the links' inertia is left out: the carrier turns slowly and evenly), frictionless hinges, an
ideal (lossless) gear train. Coordinates are absolute angles, counterclockwise from +x: theta1 of the carrier OA
(L1), theta2 of rod I AF (L2), theta4 of the receiving plate BE (L4) and phi, the direction of the push plate, in
whose frame (origin P) E and F stand at e and f. Cut at E, the loop reads

    Phi = L1 e(theta1) + L2 e(theta2) + R(phi) (e - f) - B - L4 e(theta4) = 0.

Its rate, M (theta4', phi') = -(Phi_theta1 theta1' + Phi_theta2 theta2') with M = [Phi_theta4, Phi_phi], gives the
receiving plate and the plate from the carrier and the rod; det M = cross(E - F, E - B) = L3 L4 sin(mu) up to
sign, mu the transmission angle between EF and BE at E, so it fails only at a dead point. The velocity of every
point follows: per unit carrier turn with theta1' = -1 and theta2' = rho' - 1 (the carrier turns clockwise by c,
rho(c) is the rod's angle relative to it), per unit turn of the rod about A, the carrier held, with (0, 1).

By virtual work the same M, transposed, gives the force at the cut. With f_E the force the receiving plate exerts
on the plate at E, the cut's work f_E . dPhi balances the loads' generalised forces in theta4 and phi:
M^T f_E = -(Q_4, Q_phi), Q_4 the moment about B of the loads on BE, Q_phi that about F of the loads on the plate.
"""
from __future__ import annotations

import sympy as sp

from derivations.planar import rotate, unit
from derivations.spec import Derived, symbol_group


def loop_points(lengths, angles, plate_points):
    """A, F, E (from the plate's side), P and the loop's cut Phi, for lengths (L1, L2, L4), angles (theta1, theta2,
    theta4, phi) and plate points (e_x, e_y, f_x, f_y). B is a symbol: it drops out of every rate."""
    l1, l2, l4 = lengths
    theta1, theta2, theta4, phi = angles
    hinge_b = sp.Matrix(sp.symbols("hinge_b_x hinge_b_y", real=True))
    e, f = sp.Matrix(plate_points[:2]), sp.Matrix(plate_points[2:])
    a = l1 * unit(theta1)
    hinge_f = a + l2 * unit(theta2)
    hinge_e = hinge_f + rotate(phi, e - f)
    p = hinge_f - rotate(phi, f)
    return {"a": a, "f": hinge_f, "e": hinge_e, "p": p, "b": hinge_b, "cut": hinge_e - hinge_b - l4 * unit(theta4)}


def closure_matrix(points, angles) -> sp.Matrix:
    """M = [Phi_theta4, Phi_phi]: the loop's rate in the receiving plate's and the plate's angles."""
    return points["cut"].jacobian(angles[2:])


def angle_rates(points, angles, rates) -> sp.Matrix:
    """(theta4', phi') from (theta1', theta2'), solved by Cramer's rule."""
    matrix = closure_matrix(points, angles)
    driven = -points["cut"].jacobian(angles[:2]) * sp.Matrix(rates)
    return matrix.adjugate() * driven / matrix.det()


def velocities(points, angles, rates) -> dict:
    """Velocity of each named point and link centre for the given (theta1', theta2'): A, F, E, P and the centres of
    the carrier (OA's midpoint), the rod with the planet (AF's midpoint), the plate (centroid of E, F, P) and the
    receiving plate (BE's midpoint)."""
    rate = sp.Matrix([*rates, *angle_rates(points, angles, rates)])

    def moving(position):
        return position.jacobian(angles) * rate

    a, f, e, p = (moving(points[name]) for name in ("a", "f", "e", "p"))
    return {"hinge_a": a, "hinge_f": f, "hinge_e": e, "point_p": p, "carrier_center": a / 2,
            "rod_center": (a + f) / 2, "plate_center": (e + f + p) / 3, "receiving_center": e / 2}


def plate_hinge_force(points, angles, moments) -> sp.Matrix:
    """f_E, the force of the receiving plate on the plate at E, from M^T f_E = -(Q_4, Q_phi)."""
    transposed = closure_matrix(points, angles).T
    return -transposed.adjugate() * sp.Matrix(moments) / transposed.det()


def derive() -> list[Derived]:
    lengths, angles = symbol_group("chain_lengths", 3), symbol_group("angles", 4)
    plate, rates, moments = symbol_group("plate_points", 4), symbol_group("rates", 2), symbol_group("moments", 2)
    link, plate_angles = symbol_group("receiving_length", 1), symbol_group("plate_angles", 2)
    points = loop_points(lengths, angles, plate)
    moving = velocities(points, angles, rates)
    # M holds only L4, theta4 and phi: the force takes those alone
    force = plate_hinge_force(points, angles, moments).subs(
        {lengths[2]: link[0], angles[2]: plate_angles[0], angles[3]: plate_angles[1]})
    return [
        Derived(name="fivebar_statics_velocities",
                doc="Rates (theta4', phi') and velocities of A, F, E, P and the four link centres from (theta1', "
                    "theta2'), for lengths (L1, L2, L4), angles (theta1, theta2, theta4, phi), plate points "
                    "(e_x, e_y, f_x, f_y).",
                inputs=(("chain_lengths", lengths), ("angles", angles), ("plate_points", plate), ("rates", rates)),
                outputs=(("angle_rates", tuple(angle_rates(points, angles, rates))),
                         *((name, tuple(value)) for name, value in moving.items()))),
        Derived(name="fivebar_statics_plate_hinge_force",
                doc="Force of BE on the plate at E from M^T f_E = -(Q_4, Q_phi), the moments (counterclockwise) "
                    "about B of the loads on BE and about F of the loads on the plate, for L4, angles (theta4, phi) "
                    "and plate points (e_x, e_y, f_x, f_y).",
                inputs=(("receiving_length", link), ("plate_angles", plate_angles), ("plate_points", plate),
                        ("moments", moments)),
                outputs=(("force_e", tuple(force)),)),
    ]

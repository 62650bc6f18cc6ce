"""Closure of the five-bar O-A-F-E-B of Wang et al. 2025 (Figure 8, eq 7-10).

Vectors: OA = L1 e(theta1) (carrier), AF = L2 e(theta2) (connecting rod I), EF = L3 e(theta3),
BE = L4 e(theta4) (receiving plate), and the frame OB = L5 (-cos theta5, sin theta5), the
convention under which eq (8) comes out as printed. The loop OA + AF = OB + BE + EF (eq 7)
gives, after eliminating theta3 by |EF| = L3,
    P + Q cos(theta4) + R sin(theta4) = 0                                    (eq 8)
and with t = tan(theta4 / 2) the quadratic (P - Q) t^2 + 2 R t + (P + Q) = 0 (eq 9). It has a
real root, i.e. the chain closes for the given theta1, theta2, iff
    B^2 - 4 A C = 4 (Q^2 + R^2 - P^2) >= 0                                     (eq 10).
Since sqrt(Q^2 + R^2) = 2 L4 |BF|, the scale-free margin (Q^2 + R^2 - P^2) / (Q^2 + R^2) is
sin^2 of the angle EBF: 0 where B, E, F line up (the chain jams or changes branch), 1 at best.
"""
from __future__ import annotations

import sympy as sp

from derivations.planar import cross, rotate, unit
from derivations.spec import Derived, symbol_group


def closure(lengths, theta1, theta2, theta4, theta5):
    """|OA + AF - OB - BE|^2 - L3^2, expanded (zero when the loop closes)."""
    l1, l2, l3, l4, l5 = lengths
    frame = l5 * sp.Matrix([-sp.cos(theta5), sp.sin(theta5)])
    gap = l1 * unit(theta1) + l2 * unit(theta2) - frame - l4 * unit(theta4)
    return sp.expand(gap.dot(gap) - l3**2)


def closure_parts(lengths, theta1, theta2, theta5):
    """(P, Q, R) of eq (8) written as P + Q cos(theta4) + R sin(theta4)."""
    theta4, c, s = sp.symbols("theta4 c4 s4", real=True)
    expr = sp.expand(sp.expand_trig(closure(lengths, theta1, theta2, theta4, theta5)))
    expr = sp.expand(expr.subs({sp.cos(theta4): c, sp.sin(theta4): s}).subs(s**2, 1 - c**2))
    q, r = expr.coeff(c), expr.coeff(s)
    return sp.expand(expr - q * c - r * s), q, r


def half_angle_quadratic(lengths, theta1, theta2, theta5):
    """(A, B, C) of eq (9) for t = tan(theta4 / 2)."""
    p, q, r = closure_parts(lengths, theta1, theta2, theta5)
    return p - q, 2 * r, p + q


def plate_hinges(pose, plate_points):
    """E and F of the plate in pose (x_P, y_P, direction), from their plate-frame coordinates
    (e_x, e_y, f_x, f_y) relative to P."""
    p = sp.Matrix(pose[:2])
    return (p + rotate(pose[2], sp.Matrix(plate_points[:2])), p + rotate(pose[2], sp.Matrix(plate_points[2:])))


def pose_closure(pose, plate_points, hinge_b, lengths, angles):
    """The loop of eq (7) closed at a pose of the plate, at position level: |E - B|^2 - L4^2 (E on the
    circle about B) and F - A - L2 e(theta2) (F at the end of the rod), for lengths (L1, L2, L4) and
    absolute angles (theta1 of the carrier, theta2 of the rod)."""
    e, f = plate_hinges(pose, plate_points)
    b = sp.Matrix(hinge_b)
    l1, l2, l4 = lengths
    theta1, theta2 = angles
    rod_end = f - l1 * unit(theta1) - l2 * unit(theta2)
    return ((e - b).dot(e - b) - l4**2, rod_end[0], rod_end[1])


def assembly_sine(pose, plate_points, hinge_b, receiving_length):
    """sin of the signed angle from BF to BE, |BE| taken as L4 (equal where the pose closes): its sign
    is the assembly branch of the dyad B-E-F, its square the closure margin at the pose."""
    e, f = plate_hinges(pose, plate_points)
    b = sp.Matrix(hinge_b)
    return cross(f - b, e - b) / (receiving_length * sp.sqrt((f - b).dot(f - b)))


def transmission_margin(lengths, theta1, theta2, theta5):
    """sin^2 of the angle BEF at E: by the sine rule in triangle B-E-F, sin(BEF) = |BF| sin(EBF) / L3, so
    sin^2(BEF) = margin |BF|^2 / L3^2 with the closure margin sin^2(EBF) and F - B = OA + AF - OB."""
    l1, l2, l3, _, l5 = lengths
    p, q, r = closure_parts(lengths, theta1, theta2, theta5)
    bf = l1 * unit(theta1) + l2 * unit(theta2) - l5 * sp.Matrix([-sp.cos(theta5), sp.sin(theta5)])
    return (q**2 + r**2 - p**2) / (q**2 + r**2) * bf.dot(bf) / l3**2


def triangle_margins(lengths, theta1, theta2, theta5):
    """sin^2 of the angles EBF and BEF from the triangle B-E-F alone: with BE = L4, EF = L3 and D = |BF|^2,
    F - B = OA + AF - OB, the law of cosines gives cos(EBF) = (L4^2 + D - L3^2) / (2 L4 sqrt(D)) and the sine
    rule sin^2(BEF) = sin^2(EBF) D / L3^2. The same two quantities as eq (10)'s margin and
    ``transmission_margin`` (tested), in a form a few operations long where the expanded P, Q, R are not: the
    design NLP evaluates them and their second derivatives at every grid point of every iteration."""
    l1, l2, l3, l4, l5 = lengths
    bf = l1 * unit(theta1) + l2 * unit(theta2) - l5 * sp.Matrix([-sp.cos(theta5), sp.sin(theta5)])
    squared = bf.dot(bf)
    closure = 1 - (l4**2 + squared - l3**2) ** 2 / (4 * l4**2 * squared)
    return closure, closure * squared / l3**2


def derive() -> list[Derived]:
    lengths = symbol_group("lengths", 5)
    angles = symbol_group("angles", 4)            # theta1, theta2, theta4, theta5
    crank = symbol_group("crank_angles", 3)       # theta1, theta2, theta5
    p, q, r = closure_parts(lengths, *crank)
    a, b, c = half_angle_quadratic(lengths, *crank)
    pose, plate = symbol_group("pose", 3), symbol_group("plate_points", 4)
    hinge_b, link = symbol_group("hinge_b", 2), symbol_group("receiving_length", 1)
    chain, chain_angles = symbol_group("chain_lengths", 3), symbol_group("chain_angles", 2)
    return [
        Derived(name="fivebar_closure",
                doc=("Eq (8): |OA + AF - OB - BE|^2 - L3^2 for lengths L1..L5 "
                     "and angles theta1, theta2, theta4, theta5."),
                inputs=(("lengths", lengths), ("angles", angles)),
                outputs=(("residual", (closure(lengths, angles[0], angles[1], angles[2], angles[3]),)),)),
        Derived(name="fivebar_half_angle_quadratic",
                doc="Eq (9): coefficients A, B, C in t = tan(theta4/2), for theta1, theta2, theta5.",
                inputs=(("lengths", lengths), ("crank_angles", crank)),
                outputs=(("coefficients", (a, b, c)),)),
        Derived(name="fivebar_discriminant",
                doc="Eq (10): B^2 - 4 A C = 4 (Q^2 + R^2 - P^2); the chain closes where it is >= 0.",
                inputs=(("lengths", lengths), ("crank_angles", crank)),
                outputs=(("discriminant", (4 * (q**2 + r**2 - p**2),)),)),
        Derived(name="fivebar_closure_margin",
                doc=("(Q^2 + R^2 - P^2) / (Q^2 + R^2) = sin^2(angle EBF): eq (10) without its scale, "
                     "in [0, 1] where it closes."),
                inputs=(("lengths", lengths), ("crank_angles", crank)),
                outputs=(("margin", ((q**2 + r**2 - p**2) / (q**2 + r**2),)),)),
        Derived(name="fivebar_transmission_margin",
                doc="sin^2 of the angle BEF at E = margin |BF|^2 / L3^2 (sine rule), for theta1, theta2, theta5.",
                inputs=(("lengths", lengths), ("crank_angles", crank)),
                outputs=(("margin", (transmission_margin(lengths, *crank),)),)),
        Derived(name="fivebar_triangle_margins",
                doc=("sin^2(angle EBF) and sin^2(angle BEF) from the triangle B-E-F (law of cosines in |BF|^2, "
                     "sine rule): eq (10)'s margin and the transmission margin, short, for theta1, theta2, theta5."),
                inputs=(("lengths", lengths), ("crank_angles", crank)),
                outputs=(("margins", triangle_margins(lengths, *crank)),)),
        Derived(name="fivebar_plate_hinges",
                doc="E and F of the plate in pose (x_P, y_P, direction) from plate points (e_x, e_y, f_x, f_y).",
                inputs=(("pose", pose), ("plate_points", plate)),
                outputs=tuple(zip(("hinge_e", "hinge_f"), (tuple(h) for h in plate_hinges(pose, plate)),
                                  strict=True))),
        Derived(name="fivebar_pose_closure",
                doc="Eq (7) closed at a plate pose (x_P, y_P, direction): |E - B|^2 - L4^2 and F - A - L2 e(theta2), "
                    "for plate points (e_x, e_y, f_x, f_y), hinge B, lengths (L1, L2, L4), angles (theta1, theta2).",
                inputs=(("pose", pose), ("plate_points", plate), ("hinge_b", hinge_b), ("chain_lengths", chain),
                        ("chain_angles", chain_angles)),
                outputs=(("residual", pose_closure(pose, plate, hinge_b, chain, chain_angles)),)),
        Derived(name="fivebar_assembly_sine",
                doc="sin of the signed angle from BF to BE at a plate pose, |BE| taken as L4: the assembly branch.",
                inputs=(("pose", pose), ("plate_points", plate), ("hinge_b", hinge_b),
                        ("receiving_length", link)),
                outputs=(("sine", (assembly_sine(pose, plate, hinge_b, link[0]),)),)),
    ]

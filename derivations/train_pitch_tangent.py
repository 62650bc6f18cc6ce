"""Polar tangent angle of the four pitch curves of the planetary train at the contact, scale-free.

Where two pitch curves touch, the contact point lies on the line of centres, and their common tangent
leans from the normal to that line by the polar tangent angle mu: tan(mu) = r_theta / r, with theta the
curve's own polar angle, the one the contact runs along as the carrier turns (the curves of
``train_pitch_curvature``, Wang et al. 2025 eq 11-13, in s = rho'(c), s' and k; the gear itself turns the
other way). Each curve is r = a f(theta), so r_theta / r is free of a: ``derive`` checks that a drops
out of r / a and r_theta / a.

Driver and driven side. The driven radius is a - r1 and its angle runs r1 / (a - r1) per driver radian,
so its r_theta / r is -(r1_theta / r1): both angles run the same way along the one shared tangent, and mu
is each curve's lean toward its mate's centre, which lies on opposite sides. ``derive`` checks the
identity for both stages; the generated rows give all four curves (driven = -driver).

Pressure angle. Teeth cut by a rack of pressure angle alpha0 (``gears.rack_teeth``) push along a line
through the contact at alpha0 from the common tangent. Put the driver's centre at the origin, the contact
at (r, 0) and the driven centre on +x, with theta counterclockwise: the driver turns clockwise, its point
at the contact moving along -y, and the tangent (r_theta, r) leans from the y axis toward +x by mu. A tooth
narrows toward its tip, so its leading flank's outward normal points forward (-y) and outward (+x): the
force on the driven tooth, cos(alpha0) t + sin(alpha0) n with t = -(sin mu, cos mu), n = (cos mu, -sin mu),
is (sin(alpha0 - mu), -cos(alpha0 - mu)), at alpha0 - mu from the motion. That is the drive flank (the
driver pushes the driven gear on): pressure angle alpha0 - mu of the driver, alpha0 + mu of the driven
curve, one angle. The coast flank (the load drives back) is its mirror image: alpha0 + mu of the driver.
Either way the teeth see at most alpha0 + |mu| (tests measure both flanks on rack-cut outlines).
"""
from __future__ import annotations

import sympy as sp

from derivations.spec import Derived, symbol_group
from derivations.train_pitch_curvature import CENTER_DISTANCE, CORRECTION, ROOT, curves_in_own_angle

#: Rows of ``curves_in_own_angle`` that mesh: (driver, driven) of stage 1 and stage 2.
STAGES = ((0, 1), (2, 3))


def scale_free_tangent(correction, slope_derivatives):
    """Per curve: (r / a, r_theta / a) in s, s', k, after checking that a drops out and that each stage's
    driven curve has the driver's r_theta / r with the opposite sign."""
    relative = []
    for r, r_theta, _ in curves_in_own_angle(slope_derivatives):
        pair = tuple(sp.factor(sp.cancel(v / CENTER_DISTANCE)) for v in (r, r_theta))
        if any(CENTER_DISTANCE in v.free_symbols for v in pair):
            raise AssertionError("the center distance does not cancel from the polar tangent")
        relative.append(pair)
    for driver, driven in STAGES:
        if sp.cancel(relative[driver][1] / relative[driver][0] + relative[driven][1] / relative[driven][0]) != 0:
            raise AssertionError("a driven pitch curve's tangent differs from its driver's")
    values = {ROOT: sp.sqrt(slope_derivatives[0]), CORRECTION: correction}
    return [tuple(v.subs(values) for v in pair) for pair in relative]


def derive() -> list[Derived]:
    slope = symbol_group("slope_derivatives", 2)        # rho', rho''
    k = symbol_group("correction", 1)[0]
    curves = scale_free_tangent(k, (*slope, sp.Dummy("unused")))   # rho''' only bends the curves
    tangents = [sp.cancel(rise / radius) for radius, rise in curves]
    return [
        Derived(name="train_pitch_tangent",
                doc=("Sun, first intermediate, second intermediate, planet (eq 11-13 with I1 = rho'^(-1/2)/k, "
                     "I2 = k rho'^(-1/2)): tan(mu) = r_theta / r, the lean of the pitch curves' common tangent from "
                     "the normal to the line of centres, in the curve's own polar angle (driven = -driver), "
                     "and mu = atan(r_theta / r) (rad), from rho', rho'' and k."),
                inputs=(("slope_derivatives", slope), ("correction", (k,))),
                outputs=(("tangent", tuple(tangents)),
                         ("angle", tuple(sp.atan2(*sp.fraction(t)) for t in tangents)))),   # denominator > 0: atan
    ]

"""Polar tangent angle of the four pitch curves of the planetary train at the contact, scale-free.

Where two pitch curves touch, the contact point lies on the line of centres, and their common tangent
leans from the normal to that line by the polar tangent angle mu: tan(mu) = r_theta / r, with r and its
derivative in the gear's own angle counted the way the gear turns as the carrier turns (the curves of
``train_pitch_curvature``, Wang et al. 2025 eq 11-13, in s = rho'(c), s' and k). Each curve is
r = a f(theta), so r_theta / r is free of a: ``derive`` checks that a drops out of r / a and r_theta / a.

Driver and driven side. The driven radius is a - r1 and its angle turns by r1 / (a - r1) per driver
radian, so its r_theta / r is -(r1_theta / r1): the two curves share one tangent line, and the opposite
signs only say that each angle is counted in its own gear's turning sense. ``derive`` checks the
identity for both stages; the generated rows give all four curves (driven = -driver).

Pressure angle. Teeth cut by a rack of pressure angle alpha0 (``gears.rack_teeth``) act along a line
through the contact at alpha0 from the common tangent. Put the driver's centre at the origin, the contact
at (r1, 0), the driver turning counterclockwise: the tangent (r_theta, r) leans by mu from +y toward the
driven centre. A tooth narrows toward its tip, so the leading flank's outward normal points forward and
outward: the force on the driven tooth leans by alpha0 + mu from +y, the velocity of the driven gear's
point at the contact. That is the drive flank (the driver pushes the driven gear on): pressure angle
alpha0 + mu. The coast flank (the load drives back) is its mirror image: alpha0 - mu. The pressure angle
the teeth see over a turn is therefore alpha0 + |mu| at worst, the same seen from either gear.
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
                     "the normal to the line of centres, in each gear's own turning sense (driven = -driver), "
                     "and mu = atan(r_theta / r) (rad), from rho', rho'' and k."),
                inputs=(("slope_derivatives", slope), ("correction", (k,))),
                outputs=(("tangent", tuple(tangents)),
                         ("angle", tuple(sp.atan2(*sp.fraction(t)) for t in tangents)))),   # denominator > 0: atan
    ]

"""Curvature of the four pitch curves of the planetary train (Wang et al. 2025 eq 11-13), scale-free.

The relative angle rho(c) of the rod against the carrier has slope s = rho'(c) > 0; the total
ratio is i0 = 1 / s (eq 11), split as I1 = s^(-1/2) / k and I2 = k s^(-1/2) with
k = 2 pi / int_0^2pi sqrt(s) dc (eq 12, over the sun's angle). With center distances a1, a2:

- sun:                  r = a1 / (1 + I1)   in the sun's angle c;
- first intermediate:   r = a1 - r_sun      in its own angle psi, dpsi/dc = 1 / I1;
- second intermediate:  r = a2 / (1 + I2)   in psi;
- planet:               r = a2 - r          in its own angle chi, dchi/dpsi = 1 / I2.

Each curve is r = a f(theta) with f free of a, so its polar convexity (the onion-transplanter paper, eq 8)
r^2 + 2 r_theta^2 - r r_theta_theta is a^2 times that of f, and its curvature radius
(r^2 + r_theta^2)^(3/2) / (r^2 + 2 r_theta^2 - r r_theta_theta) is a times that of f:
``derive`` checks that a drops out of both before dividing it away. Derivatives in a curve's
own angle follow from d/dtheta = (dc/dtheta) d/dc, so everything is in s, s', s'' and k. A
convex curve has positive convexity; the direction in which its angle is counted does not
matter (r_theta changes sign, r_theta_theta does not).
"""
from __future__ import annotations

import sympy as sp

from derivations.gears import polar_convexity
from derivations.spec import Derived, symbol_group

CURVES = ("sun", "first_intermediate", "second_intermediate", "planet")

_c = sp.Symbol("c", real=True)
_slope = sp.Function("s", positive=True)(_c)


def train_curves(correction, center_distance):
    """(radius, dc/dtheta) of each curve of ``CURVES`` as functions of the carrier turn c, with
    s(c) = rho'(c), one center distance for both stages (each stage's own a scales its two curves)."""
    first = 1 / (correction * sp.sqrt(_slope))
    second = correction / sp.sqrt(_slope)
    sun = center_distance / (1 + first)
    second_intermediate = center_distance / (1 + second)
    return [(sun, 1), (center_distance - sun, first), (second_intermediate, first),
            (center_distance - second_intermediate, first * second)]


def _in_own_angle(radius, rate):
    """r, dr/dtheta, d2r/dtheta2 for a curve whose angle theta turns by 1/rate per unit c."""
    slope = rate * sp.diff(radius, _c)
    return radius, slope, rate * sp.diff(slope, _c)


#: The center distance a, root = sqrt(s) and the correction k, as ``curves_in_own_angle`` writes them.
CENTER_DISTANCE, ROOT, CORRECTION = sp.symbols("a root k", positive=True)


def curves_in_own_angle(slope_derivatives):
    """Per curve of ``CURVES``: r, dr/dtheta, d2r/dtheta2 in its own angle, in ``CENTER_DISTANCE``, ``ROOT``,
    ``CORRECTION`` and s', s'' (``slope_derivatives[1:]``; substitute sqrt(s) for ``ROOT``)."""
    _, s1, s2 = slope_derivatives
    rates = {sp.Derivative(_slope, (_c, 2)): s2, sp.Derivative(_slope, _c): s1, _slope: ROOT**2}
    return [tuple(sp.together(v.subs(rates)) for v in _in_own_angle(radius, rate))
            for radius, rate in train_curves(CORRECTION, CENTER_DISTANCE)]


def scale_free_curvature(correction, slope_derivatives):
    """Per curve: convexity / a^2, curvature a kappa and curvature radius / a, in s, s', s'', k."""
    a, root, k = CENTER_DISTANCE, ROOT, CORRECTION
    s0 = slope_derivatives[0]
    out = []
    for r, r_theta, r_theta2 in curves_in_own_angle(slope_derivatives):
        convexity = polar_convexity(r, r_theta, r_theta2)
        speed_squared = r**2 + r_theta**2
        relative_convexity = sp.factor(sp.cancel(convexity / a**2))
        relative_speed = sp.factor(sp.cancel(speed_squared / a**2))
        if a in relative_convexity.free_symbols or a in relative_speed.free_symbols:
            raise AssertionError("the center distance does not cancel from the pitch curvature")
        curvature = relative_convexity / relative_speed ** sp.Rational(3, 2)
        out.append(tuple(v.subs({root: sp.sqrt(s0), k: correction})
                         for v in (relative_convexity, curvature, 1 / curvature)))
    return out


def derive() -> list[Derived]:
    slope = symbol_group("slope_derivatives", 3)        # rho', rho'', rho'''
    k = symbol_group("correction", 1)[0]
    curves = scale_free_curvature(k, slope)
    return [
        Derived(name="train_pitch_curvature",
                doc=("Sun, first intermediate, second intermediate, planet (eq 11-13 with I1 = rho'^(-1/2)/k, "
                     "I2 = k rho'^(-1/2)): polar convexity / a^2 (convex where positive), curvature times the "
                     "stage's center distance a, and curvature radius / a, from rho', rho'', rho''' and k."),
                inputs=(("slope_derivatives", slope), ("correction", (k,))),
                outputs=(("convexity", tuple(v[0] for v in curves)),
                         ("curvature", tuple(v[1] for v in curves)),
                         ("curvature_radius", tuple(v[2] for v in curves)))),
    ]

"""A pair of external non-circular gears: conjugate pitch curves, curvature, kinematics, closure.

Notation. Driver pitch curve r1(phi1) about its center, driven r2(phi2), center distance a.
Pure rolling at the contact point on the line of centers gives (the onion-transplanter paper, eq 4)
    r2 = a - r1,   dphi2/dphi1 = r1 / (a - r1),
and the transmission ratio i12 = omega1 / omega2 = (a - r1) / r1 (the onion-transplanter paper, eq 13).

- Curvature radius of a polar curve (the onion-transplanter paper, eq 8):
    rho = (r^2 + r'^2)^(3/2) / (r^2 + 2 r'^2 - r r''); the curve is convex where the
    denominator (``convexity``) is positive.
- The driven curve's r2, dr2/dphi2, d2r2/dphi2^2 follow from r1 and its phi1-derivatives by
  the chain rule with dphi2/dphi1 = r1 / r2 (``conjugate_pitch``).
- Driven speed omega2 = omega1 r1 / (a - r1); acceleration (constant omega1)
  omega1^2 d/dphi1 [r1 / (a - r1)] = omega1^2 a r1' / (a - r1)^2
  (the onion-transplanter paper, eq 14-15).
- Closure with orders (n1, n2): int_0^2pi r1 / (a - r1) dphi1 = 2 pi n1 / n2. For the
  ellipse family r1 = p / (1 - e cos(n phi)), p = A (1 - e^2), and the limacon family
  r1 = b + c cos(n phi), the integral is elementary (int dphi / (u - v cos(n phi)) =
  2 pi / sqrt(u^2 - v^2) over a period), and closure becomes a quadratic in a whose larger
  root is the center distance (``*_center_distance``).
- A pair given by its ratio i12 (Wang et al. 2025 eq 13): r1 = a / (1 + i12) solves
  i12 = (a - r1) / r1, and pure rolling then turns the driven gear by dphi2/dphi1 = 1 / i12
  (``ratio_pair_pitch``). Eq (13) prints phi2 = int I1 dphi1, the ratio itself, which
  contradicts its own first line; ``driven_rate_for_ratio`` shows the reciprocal.
- Limacon convexity (the onion-transplanter paper, eq 9-10): with r1 = l (1 + k cos(m phi)) and C = cos(m phi),
  the driver's and the driven curve's convexity as polynomials in C (``limacon_*_convexity``).
"""
from __future__ import annotations

import sympy as sp

from derivations.spec import Derived, symbol_group

phi = sp.Symbol("phi", real=True)


def polar_convexity(r, slope, bend):
    """Denominator of eq (8): positive where the polar curve is convex."""
    return r**2 + 2 * slope**2 - r * bend


def conjugate_derivatives(center_distance, r1_of_phi):
    """(r2, dr2/dphi2, d2r2/dphi2^2, dphi2/dphi1) as expressions in phi1 for a driver r1(phi1)."""
    r2 = center_distance - r1_of_phi
    speed = r1_of_phi / r2
    slope = sp.diff(r2, phi) / speed
    bend = sp.diff(slope, phi) / speed
    return r2, slope, bend, speed


def _replace_derivatives(expr, function, radius, slope, bend):
    return expr.subs({sp.Derivative(function, (phi, 2)): bend}).subs(
        {sp.Derivative(function, phi): slope}).subs({function: radius})


def _curvature() -> Derived:
    r, slope, bend = symbol_group("radius", 1)[0], symbol_group("slope", 1)[0], symbol_group("bend", 1)[0]
    convexity = polar_convexity(r, slope, bend)
    return Derived(
        name="polar_curvature",
        doc="Curvature radius (eq 8) and its denominator, positive where the curve is convex.",
        inputs=(("radius", (r,)), ("slope", (slope,)), ("bend", (bend,))),
        outputs=(("curvature_radius", ((r**2 + slope**2) ** sp.Rational(3, 2) / convexity,)),
                 ("convexity", (convexity,))),
    )


def _conjugate() -> Derived:
    a = symbol_group("center_distance", 1)[0]
    r, slope, bend = symbol_group("radius", 1)[0], symbol_group("slope", 1)[0], symbol_group("bend", 1)[0]
    r1 = sp.Function("r1")(phi)
    outputs = [_replace_derivatives(sp.simplify(e), r1, r, slope, bend) for e in conjugate_derivatives(a, r1)]
    return Derived(
        name="conjugate_pitch",
        doc=("Driven pitch radius and its derivatives with respect to phi2, and dphi2/dphi1, from the "
             "driver's radius, slope and bend (derivatives with respect to phi1)."),
        inputs=(("center_distance", (a,)), ("radius", (r,)), ("slope", (slope,)), ("bend", (bend,))),
        outputs=(("driven_radius", (outputs[0],)), ("driven_slope", (outputs[1],)),
                 ("driven_bend", (outputs[2],)), ("speed_ratio", (outputs[3],))),
    )


def _kinematics() -> Derived:
    a = symbol_group("center_distance", 1)[0]
    r, slope, speed = symbol_group("radius", 1)[0], symbol_group("slope", 1)[0], symbol_group("driver_speed", 1)[0]
    r1 = sp.Function("r1")(phi)
    driven_speed = speed * r1 / (a - r1)
    acceleration = sp.simplify(speed * sp.diff(driven_speed, phi))
    return Derived(
        name="pair_kinematics",
        doc="Ratio i12 = omega1/omega2 (eq 13), driven angular velocity (eq 14) and acceleration (eq 15).",
        inputs=(("center_distance", (a,)), ("radius", (r,)), ("slope", (slope,)), ("driver_speed", (speed,))),
        outputs=(("ratio", ((a - r) / r,)), ("driven_speed", (driven_speed.subs(r1, r),)),
                 ("driven_acceleration", (_replace_derivatives(acceleration, r1, r, slope, 0),))),
    )


def driver_radius_for_ratio(center_distance, ratio):
    """r1 for which the pair's ratio i12 = (a - r1) / r1 equals ``ratio``: a / (1 + i12)."""
    r1 = sp.Symbol("r1", positive=True)
    (root,) = sp.solve(sp.Eq((center_distance - r1) / r1, ratio), r1)
    return root


def driven_rate_for_ratio(center_distance, ratio):
    """dphi2/dphi1 of pure rolling (``conjugate_derivatives``) at the r1 of ``driver_radius_for_ratio``."""
    *_, speed = conjugate_derivatives(center_distance, driver_radius_for_ratio(center_distance, ratio))
    return sp.simplify(speed)


def _ratio_pair() -> Derived:
    a, ratio = symbol_group("center_distance", 1)[0], symbol_group("ratio", 1)[0]
    return Derived(
        name="ratio_pair_pitch",
        doc=("Driver pitch radius and the driven gear's turn per driver turn dphi2/dphi1 for a pair "
             "with ratio i12 = omega1/omega2 (Wang et al. 2025 eq 13; the rate is 1/i12, not i12)."),
        inputs=(("center_distance", (a,)), ("ratio", (ratio,))),
        outputs=(("driver_radius", (driver_radius_for_ratio(a, ratio),)),
                 ("driven_rate", (driven_rate_for_ratio(a, ratio),))),
    )


def larger_root(equation, a):
    """Larger root in ``a`` of a quadratic whose a^2 coefficient is positive: (-B + sqrt(B^2 - 4AC)) / 2A."""
    big, middle, small = sp.Poly(sp.expand(equation.lhs - equation.rhs), a).all_coeffs()
    return (-middle + sp.sqrt(middle**2 - 4 * big * small)) / (2 * big)


def ellipse_center_distance_expr(semi_major_axis, eccentricity, order_ratio):
    """Closure of r1 = p / (1 - e cos(n phi)), p = A (1 - e^2): r1/(a - r1) = p / ((a - p) - a e cos(n phi)),
    so 2 pi p / sqrt((a - p)^2 - a^2 e^2) = 2 pi / q with q = n2 / n1; a^2 coefficient 1 - e^2 > 0."""
    a = sp.Symbol("a", positive=True)
    p = semi_major_axis * (1 - eccentricity**2)
    return larger_root(sp.Eq((a - p) ** 2 - a**2 * eccentricity**2, (p * order_ratio) ** 2), a)


def limacon_center_distance_expr(base, amplitude, order_ratio):
    """Closure of r1 = b + c cos(n phi): r1/(a - r1) = a / ((a - b) - c cos(n phi)) - 1, so
    2 pi a / sqrt((a - b)^2 - c^2) - 2 pi = 2 pi / q with q = n2 / n1; a^2 coefficient (1 + 1/q)^2 - 1 > 0."""
    a = sp.Symbol("a", positive=True)
    ratio = 1 + 1 / order_ratio
    return larger_root(sp.Eq(ratio**2 * ((a - base) ** 2 - amplitude**2), a**2), a)


def _closed_forms() -> list[Derived]:
    a_axis, e = symbol_group("semi_major_axis", 1)[0], symbol_group("eccentricity", 1)[0]
    q = symbol_group("order_ratio", 1)[0]
    base, amplitude = symbol_group("base", 1)[0], symbol_group("amplitude", 1)[0]
    return [
        Derived(name="ellipse_center_distance",
                doc="Center distance that closes an (order-n) ellipse driver with orders n1, n2; order_ratio = n2/n1.",
                inputs=(("semi_major_axis", (a_axis,)), ("eccentricity", (e,)), ("order_ratio", (q,))),
                outputs=(("center_distance", (ellipse_center_distance_expr(a_axis, e, q),)),)),
        Derived(name="limacon_center_distance",
                doc=("Center distance that closes a limacon driver b + c cos(n phi) with orders n1, n2; "
                     "order_ratio = n2/n1."),
                inputs=(("base", (base,)), ("amplitude", (amplitude,)), ("order_ratio", (q,))),
                outputs=(("center_distance", (limacon_center_distance_expr(base, amplitude, q),)),)),
    ]


def limacon_driver_convexity(k, m, c):
    """Convexity of r = l (1 + k cos(m phi)) divided by l^2, as a polynomial in C = cos(m phi)."""
    r = 1 + k * sp.cos(m * phi)
    expr = polar_convexity(r, sp.diff(r, phi), sp.diff(r, phi, 2))
    return sp.expand(sp.expand(expr).subs(sp.sin(m * phi) ** 2, 1 - sp.cos(m * phi) ** 2).subs(sp.cos(m * phi), c))


def limacon_driven_convexity(k, m, d, c):
    """Sign-carrying factor of the driven curve's convexity for r1 = l (1 + k cos(m phi)), a = d l.

    The convexity of the driven curve equals (a - r1)^2 / r1^3 times
    r1^3 - r1^2 r1'' + a r1 r1'' - a r1'^2 + 2 r1 r1'^2, which is returned divided by l^3.
    """
    r1 = sp.Function("r1")(phi)
    r2, slope, bend, _ = conjugate_derivatives(d, r1)
    factor = sp.factor(sp.together(polar_convexity(r2, slope, bend) * r1**3 / (d - r1) ** 2))
    r = 1 + k * sp.cos(m * phi)
    expr = sp.expand(factor.subs(r1, r).doit())
    return sp.expand(expr.subs(sp.sin(m * phi) ** 2, 1 - sp.cos(m * phi) ** 2).subs(sp.cos(m * phi), c))


def _limacon_convexity() -> list[Derived]:
    k, m, d, c = (symbol_group(n, 1)[0] for n in ("eccentricity", "order", "relative_center_distance", "cosine"))
    return [
        Derived(name="limacon_driver_convexity",
                doc="Driver convexity / l^2 for r = l (1 + k cos(m phi)) at C = cos(m phi); convex where positive.",
                inputs=(("eccentricity", (k,)), ("order", (m,)), ("cosine", (c,))),
                outputs=(("convexity", (limacon_driver_convexity(k, m, c),)),)),
        Derived(name="limacon_driven_convexity",
                doc="Sign of the driven curve's convexity for a limacon driver, a = d l, at C = cos(m phi).",
                inputs=(("eccentricity", (k,)), ("order", (m,)), ("relative_center_distance", (d,)), ("cosine", (c,))),
                outputs=(("convexity", (limacon_driven_convexity(k, m, d, c),)),)),
    ]


def derive() -> list[Derived]:
    return [_curvature(), _conjugate(), _kinematics(), _ratio_pair(), *_closed_forms(), *_limacon_convexity()]

"""Reverse design of a planetary arm: two-link inverse kinematics and the monotonicity criterion
(the rice-transplanter and reverse-gear-design papers), the idler train's ratio (the rice-transplanter paper,
eq 5-9), the pick-up tip (the cusp-pitch-curve paper, eq 15).

The arm tip is P = s e(theta) + l e(psi) about the carrier pivot: theta the carrier's direction
(pivot -> planet center), psi the arm's, gamma = psi - theta the arm relative to the carrier.

- Inverse kinematics (the reverse-gear-design paper): with r = |P| and phi3 = atan2(y, x), the elbow angle
  phi4 in [0, pi] has cos phi4 = (s^2 + r^2 - l^2) / (2 s r); its sine comes from the
  factored product (l - s + r)(l + s - r)(r + s - l)(r + s + l) / (2 s r)^2, which keeps its
  digits where the arm straightens or folds. theta = phi3 + branch * phi4 (branch +1:
  approach, -1: retraction).
- Rates along a path parameter u (the rice-transplanter paper's eq 3-4 is the first-order step of the same
  system): differentiating P(u) = s e(theta) + l e(psi) k times gives
  s theta^(k) e_perp(theta) + l psi^(k) e_perp(psi) = known terms, solved here in closed form.
- Monotonicity (the reverse-gear-design paper): the carrier turns uniformly, so theta(u) must be monotonic, and
  the gears never reverse, so gamma must be strictly monotonic in theta. The derivation
  gives d gamma / d theta = -(P . P') / (l P' . e(psi)): the planet stops against the carrier
  wherever the distance |P| from the pivot is stationary unless the arm is straight or
  folded there (then P' . e(psi) vanishes too).
- Arm lengths (the rice-transplanter paper, eq 1-2): the reachable annulus |s - l| <= r <= s + l fitted to the
  path's farthest and nearest points.
"""
from __future__ import annotations

import sympy as sp

from derivations.planar import unit
from derivations.spec import Derived, symbol_group


def inverse_angles(x, y, carrier_length, arm_length, branch):
    """(theta, psi) of the tip (x, y) on the given branch, for carrier length s and arm length l."""
    r = sp.sqrt(x**2 + y**2)
    product = ((arm_length - carrier_length + r) * (arm_length + carrier_length - r)
               * (r + carrier_length - arm_length) * (r + carrier_length + arm_length))
    elbow = sp.atan2(sp.sqrt(sp.Max(product, 0)), carrier_length**2 + r**2 - arm_length**2)
    theta = sp.atan2(y, x) + branch * elbow
    psi = sp.atan2(y - carrier_length * sp.sin(theta), x - carrier_length * sp.cos(theta))
    return theta, psi


def path_rates(theta, psi, carrier_length, arm_length, path_derivatives, order=3):
    """theta^(k), psi^(k) for k = 1..order from P', P'', P''' by implicit differentiation."""
    u = sp.Symbol("u", real=True)
    th, ps = sp.Function("th")(u), sp.Function("ps")(u)
    closure = carrier_length * unit(th) + arm_length * unit(ps)
    unknowns = [(sp.Symbol(f"dth{k}"), sp.Symbol(f"dps{k}")) for k in range(1, order + 1)]
    known = {}
    for k in range(1, order + 1):
        equations = closure.diff(u, k) - sp.Matrix(path_derivatives[2 * (k - 1):2 * k])
        for j in range(k, 0, -1):          # highest derivative first, so lower ones are not hit inside it
            equations = equations.subs({th.diff(u, j): unknowns[j - 1][0], ps.diff(u, j): unknowns[j - 1][1]})
        equations = equations.subs({th: theta, ps: psi})
        solution = sp.solve(list(equations), unknowns[k - 1], dict=True)[0]
        known.update({symbol: solution[symbol].subs(known) for symbol in unknowns[k - 1]})
    return [known[symbol] for pair in unknowns for symbol in pair]


def relative_per_carrier(theta, psi, carrier_length, arm_length, dx, dy):
    """d gamma / d theta = psi' / theta' - 1 along the path."""
    theta1, psi1 = path_rates(theta, psi, carrier_length, arm_length, (dx, dy), order=1)
    return sp.simplify(psi1 / theta1 - 1)


def arm_lengths(farthest, nearest):
    """(s, l) with s + l = Lmax and l - s = Lmin (the arm the longer link, as the rice-transplanter paper takes it)."""
    carrier_length, arm_length = sp.symbols("s l", positive=True)
    solution = sp.solve([carrier_length + arm_length - farthest, arm_length - carrier_length - nearest],
                        [carrier_length, arm_length], dict=True)[0]
    return solution[carrier_length], solution[arm_length]


def idler_total_ratio(sun_radius, planet_radius, center_distance):
    """i13 = omega_sun / omega_planet (carrier frame) of sun-idler-planet with equal center
    distances L: equal pitch-point speeds r1 w1 = (L - r1) w2 and (L - r3) w2 = r3 w3."""
    w1, w2, w3 = sp.symbols("w1 w2 w3", positive=True)
    speeds = sp.solve([sun_radius * w1 - (center_distance - sun_radius) * w2,
                       (center_distance - planet_radius) * w2 - planet_radius * w3], [w2, w3], dict=True)[0]
    return sp.simplify(w1 / speeds[w3])


def pickup_tip(first, second, arm, carrier, bend, planet, mounting):
    """The cusp-pitch-curve paper's eq (15): pivot -> O1 (first, at the carrier angle) -> O2 (second, bent by
    ``bend``) -> needle tip (arm, turned by the planet's relative angle and its mounting)."""
    return first * unit(carrier) + second * unit(carrier + bend) + arm * unit(carrier + bend + planet + mounting)


def derive() -> list[Derived]:
    point, lengths = symbol_group("point", 2), symbol_group("lengths", 2)
    branch = sp.Symbol("branch", real=True)
    angles = symbol_group("angles", 2)
    path = symbol_group("path", 6)
    carrier_length, arm_length = lengths
    theta, psi = inverse_angles(*point, carrier_length, arm_length, branch)
    extremes = symbol_group("extremes", 2)
    radii, center = symbol_group("radii", 2), sp.Symbol("center_distance", positive=True)
    pickup_lengths, pickup_angles = symbol_group("pickup_lengths", 3), symbol_group("pickup_angles", 4)
    return [
        Derived(name="two_link_inverse",
                doc=("Carrier and arm directions (theta, psi) of the tip point for lengths (s, l) "
                     "on a branch (+1 approach, -1 retraction)."),
                inputs=(("point", point), ("lengths", lengths), ("branch", (branch,))),
                outputs=(("angles", (theta, psi)),)),
        Derived(name="two_link_rates",
                doc=("theta', psi', theta'', psi'', theta''', psi''' along the path "
                     "from (theta, psi), (s, l) and P', P'', P'''."),
                inputs=(("angles", angles), ("lengths", lengths), ("path", path)),
                outputs=(("rates", tuple(path_rates(*angles, carrier_length, arm_length, path))),)),
        Derived(name="planetary_relative_per_carrier",
                doc=("Monotonicity criterion: d gamma / d theta = -(P . P') / (l P' . e(psi)); "
                     "the gears never reverse where it keeps one sign."),
                inputs=(("angles", angles), ("lengths", lengths), ("path", path[:2])),
                outputs=(("slope", (relative_per_carrier(*angles, carrier_length, arm_length, *path[:2]),)),)),
        Derived(name="arm_lengths_from_extremes",
                doc=("The rice-transplanter paper's eq (1-2): carrier s and arm l from the farthest and nearest path "
                     "points (Lmax, Lmin)."),
                inputs=(("extremes", extremes),),
                outputs=(("lengths", arm_lengths(*extremes)),)),
        Derived(name="idler_total_ratio",
                doc=("The rice-transplanter paper's eq (5-9): i13 of sun-idler-planet from the sun's and the planet's "
                     "contact radii and the center distance."),
                inputs=(("radii", radii), ("center_distance", (center,))),
                outputs=(("ratio", (idler_total_ratio(*radii, center),)),)),
        Derived(name="pickup_tip",
                doc=("The cusp-pitch-curve paper's eq (15): needle tip from L1, L2, S and the carrier angle, bend "
                     "delta0, planet turn, mounting alpha0."),
                inputs=(("pickup_lengths", pickup_lengths), ("pickup_angles", pickup_angles)),
                outputs=(("tip", tuple(pickup_tip(*pickup_lengths, *pickup_angles))),)),
    ]

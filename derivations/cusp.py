"""Pitch curves with corners (the cusp-pitch-curve paper): curvature centres, corners seen by the driven gear.

Notation. A polar pitch curve r(phi) about the gear centre, point P = r u(phi) with
u = (cos phi, sin phi); slope r' and bend r'' are derivatives with respect to phi.

- Curvature centre (eq 1 of the cusp-pitch-curve paper, written there with y(x)): with P' and P'' the phi-derivatives,
  K = P + |P'|^2 / (P' x P'') * k x P' (k the unit normal to the plane). The cross product
  P' x P'' = r^2 + 2 r'^2 - r r'' is the convexity of ``gears.polar_convexity``: a straight
  segment has it identically zero, so the package marks straight segments and gives them an
  infinite radius instead of dividing by a rounding error (``polar_curvature_center``).
- Corners. The tangent makes the angle mu = atan2(r, r') with the radius, so the tangent's
  direction is phi + mu; at a joint where r is continuous and r' jumps, the tangent turns by
  the jump of mu (a cusp; positive is a left turn, a convex corner on a counterclockwise curve).
- The driven curve at a driver corner. Pure rolling (``gears.conjugate_derivatives``) gives
  r2 = a - r1 and dphi2/dphi1 = r1 / r2. The driven curve in its own counterclockwise angle
  theta2 = -phi2 has dr2/dtheta2 = -dr2/dphi2, and its radius-tangent angle
  mu2 = atan2(r2, dr2/dtheta2) reduces to atan2(r1, r1') = mu1 (``corner_angles``; a test
  checks the identity). Its counterclockwise direction runs against phi1, so the driven
  curve turns by -(the driver's turn): a convex corner of the driver meets a concave corner
  of the same angle on the driven gear, at the same place on the line of centres.

Incomplete cycloid flanks near a corner (the cusp-pitch-curve paper, eq 7-12, re-derived):

- A circle of radius r rolling outside a base line (contact at arc sigma, frame T, outward n)
  carries the point P = B(sigma) + r n - r (cos(theta) n + side sin(theta) T), theta = sigma / r
  (side +1 rolling towards +T, -1 towards -T): at theta = 0 the point touches the base, at
  theta = pi it is at the top, 2 r above the contact (``cycloid_trace``). On a curved base with
  the same (B, T, n) at each contact this is the roulette of eq (9-12) with a1 = b1 = 1,
  and the rolling circle of eq (7) is r_gy = S / (2 pi n) for S rolled in n turns.
- The arch leans theta/2 off the normal at theta (dP/dtheta ~ (sin(theta/2), cos(theta/2)) in
  (T, n)), so it starts normal to the pitch curve: a pressure angle of 0 against the involute's
  alpha, the kink of the paper's Figure 8. The package's incomplete cycloid keeps the rolling on the
  pitch curve itself, so that its normal at theta, through the rolling contact, meets the pitch
  curve there and the arch is conjugate to its envelope; it joins the flank where the arch leans
  alpha as the involute does (theta0 = 2 alpha). From the pitch point A the flank goes on
  straight, leaning alpha as a rack's flank does, up to that joint, r (1 - cos 2 alpha) above the
  pitch curve; the arch's circle then rolls on, and its contact reaches the corner, a zone S after
  A, when the circle has turned theta_J: S = r (theta_J - 2 alpha + 2 tan alpha)
  (``incomplete_cycloid``). At the corner the circle pivots about J through the tangent's turn
  (its point draws an arc about J) and rolls on along the next segment until the arch reaches the
  tip, so the flank drives past the corner. The pair's contact meets the arch with pressure angle
  theta / 2: alpha at the joint, theta_J / 2 as the corner passes the line of centres. A lowered
  rolling base (an earlier version) put the joint on the pitch curve but its normals missed the
  pitch point, and the pair lost 0.02 mm of transmission at the corners.
- The paper's elliptic rolling curve, eq (7) r(theta) = r_gy / sqrt((a1 cos theta)^2 + (b1 sin theta)^2)
  put into eq (12), starts (theta = 0) with the velocity (1 - 1/a1) T per unit rolled arc
  (``paper_variable_cycloid_start``): along the pitch curve, a pressure angle of 90 deg, for any
  a1 != 1; for a1 = 1 it starts along the normal like the circle (pressure angle 0) whatever b1.
  No eccentricity gives an intermediate starting pressure angle, so the package joins the flanks
  with the incomplete arch above instead.

Variable involute (the cusp-pitch-curve paper, eq 1-6, re-derived):

- A pinion cutter of pitch radius r_j and base radius r_b = r_j cos(alpha) rolls outside the pitch curve.
  In the frame of the current contact M2 (tangent T, outward normal n) its centre is I = r_j n, and
  it turns relative to that frame by the rolled arc over r_j (the frame itself turns with the
  tangent). Take the cutter's involute whose pitch point lies an arc delta along the pitch circle
  from M2 (delta = s_f - s: s_f where the gear flank crosses the pitch curve, s the contact). The
  gear flank point it generates is the involute point whose normal passes through M2
  (r_j sin(beta + t) + r_b = 0 for the involute I + r_b (e(beta + t) - t e'(beta + t))), and it is
  X - M2 = delta cos^2(alpha) T - side delta sin(alpha) cos(alpha) n (``shaper_contact``): r_j drops
  out. The variable involute is the same curve whatever the cutter's size, and it is the rack's
  (``gears.rack_teeth``). The printed steps of eq 5 hold: |S I| = sqrt(r_b^2 + S N^2) with
  S N = r_b (tan(alpha) + phi_s), tan(alpha_s) = tan(alpha) + phi_s and the angle S I M2 = alpha_s - alpha,
  with phi_s = side delta / r_j and the slip coefficient f(mu) = 1.
- Eq 2-3 put the cutter's centre at P + r_j (P - Q) / rho, Q the curvature centre: outside the gear on a
  convex stretch only. On a concave stretch Q lies outside, so (P - Q) / rho points into the gear; the
  cutter belongs on the other side, which eq 10's judgement coefficient f = -1 gives for the rolling
  circle but eq 2-3 leave out. On a straight segment eq 1 divides by y'' = 0.
- The cutter's involute runs from its base circle (or its root circle, if higher) to its tip circle, so
  it generates the flank while q = -side delta lies in [r_j (tan(alpha) - t_tip), r_j (tan(alpha) - t_low)]
  with t = sqrt((R / r_b)^2 - 1) at those radii (``shaper_reach``): the contact then stays between the
  line of action's tangent point on the base circle, r_j sin(alpha) outward from M2, and the tip circle.
  Beyond the outward end the cutter's radial root trims the gear's tip: on a straight segment above
  r_j sin^2(alpha), 0.94 modules for 16 teeth at 20 deg.
"""
from __future__ import annotations

import sympy as sp

from derivations.gears import _replace_derivatives, conjugate_derivatives, phi
from derivations.spec import Derived, symbol_group


def polar_point(r):
    return sp.Matrix([r * sp.cos(phi), r * sp.sin(phi)])


def curvature_center(r_of_phi):
    """Curvature centre K = P + |P'|^2 / (P' x P'') k x P' of the polar curve r(phi) (the cusp-pitch-curve paper,
    eq 1)."""
    point = polar_point(r_of_phi)
    d1, d2 = point.diff(phi), point.diff(phi, 2)
    cross = d1[0] * d2[1] - d1[1] * d2[0]
    speed2 = d1[0] ** 2 + d1[1] ** 2
    return point + speed2 / cross * sp.Matrix([-d1[1], d1[0]]), cross


def driven_radius_and_rate(center_distance, r1_of_phi):
    """(r2, dr2/dtheta2) of the driven curve in its own counterclockwise angle theta2 = -phi2."""
    r2, slope2, _, _ = conjugate_derivatives(center_distance, r1_of_phi)
    return r2, -slope2


def _curvature_center() -> Derived:
    r, slope, bend = (symbol_group(name, 1)[0] for name in ("radius", "slope", "bend"))
    angle = symbol_group("phi", 1)[0]
    f = sp.Function("r")(phi)
    center, cross = curvature_center(f)
    center = [sp.simplify(_replace_derivatives(c, f, r, slope, bend)).subs(phi, angle) for c in center]
    return Derived(
        name="polar_curvature_center",
        doc=("Curvature centre (the cusp-pitch-curve paper, eq 1) of a polar pitch curve from r, r', r'' at phi, "
             "and P' x P'' (zero on a line)."),
        inputs=(("radius", (r,)), ("slope", (slope,)), ("bend", (bend,)), ("phi", (angle,))),
        outputs=(("center", tuple(center)), ("cross", (sp.simplify(_replace_derivatives(cross, f, r, slope, bend)),))),
    )


def _corner_angles() -> Derived:
    a = symbol_group("center_distance", 1)[0]
    r, slope = symbol_group("radius", 1)[0], symbol_group("slope", 1)[0]
    f = sp.Function("r1")(phi)
    r2, rate2 = (sp.simplify(_replace_derivatives(e, f, r, slope, 0)) for e in driven_radius_and_rate(a, f))
    return Derived(
        name="corner_angles",
        doc=("Radius-tangent angles mu1 = atan2(r1, r1') of the driver and mu2 of the driven curve in its own "
             "counterclockwise angle (equal: the driven corner turns the other way)."),
        inputs=(("center_distance", (a,)), ("radius", (r,)), ("slope", (slope,))),
        outputs=(("driver_angle", (sp.atan2(r, slope),)), ("driven_angle", (sp.atan2(r2, rate2),))),
    )


def cycloid_trace(base_x, base_y, tangent_angle, radius, theta, side):
    """Point carried by a circle of ``radius`` rolling outside the base at (base_x, base_y) with tangent
    direction ``tangent_angle`` after turning ``theta`` (the cusp-pitch-curve paper, eq 9-12 with a circle)."""
    t = sp.Matrix([sp.cos(tangent_angle), sp.sin(tangent_angle)])
    n = sp.Matrix([sp.sin(tangent_angle), -sp.cos(tangent_angle)])     # outward on a counterclockwise curve
    return sp.Matrix([base_x, base_y]) + radius * n - radius * (sp.cos(theta) * n + side * sp.sin(theta) * t)


def incomplete_cycloid(alpha, zone, corner_angle):
    """(start angle theta0, radius r, cusp offset c, joint height, height over the corner) of the arch that
    goes on from a straight flank leaning ``alpha`` off the normal at its pitch point A, rolling on the pitch
    curve itself, with its rolling contact on the corner, a ``zone`` of pitch arc after A, at ``corner_angle``.

    On the base line through A = 0 (run towards +x) the arch is the cycloid of cusp c; it leans alpha, as the
    straight flank x = h tan(alpha) does, at theta0, where it must lie on that flank."""
    r, theta, c = sp.symbols("r theta c", real=True)
    x, y = cycloid_trace(c + r * theta, 0, 0, r, theta, 1)
    y = -y                                          # tangent angle 0: the outward normal is -y; height above is -y
    lean = sp.atan2(sp.diff(x, theta), sp.diff(y, theta))
    theta0 = sp.solve(sp.Eq(sp.tan(lean), sp.tan(alpha)), theta)[0].subs(sp.atan(sp.tan(alpha)), alpha)
    cusp = sp.solve(sp.Eq(x.subs(theta, theta0), y.subs(theta, theta0) * sp.tan(alpha)), c)[0]
    radius = sp.solve(sp.Eq(cusp + r * corner_angle, zone), r)[0]
    def tidy(expression):                           # in sines and cosines, which the generated code knows
        return sp.simplify(expression.subs(sp.tan(alpha), sp.sin(alpha) / sp.cos(alpha)))

    return (sp.simplify(theta0), tidy(radius), tidy(cusp.subs(r, radius)), tidy(y.subs(theta, theta0).subs(r, radius)),
            tidy(y.subs(theta, corner_angle).subs(r, radius)))


def paper_variable_cycloid_start(a1, b1):
    """Velocity per unit rolled arc at theta = 0 of the cusp-pitch-curve paper's eq (7) + (12) on a straight base
    (components along T, n)."""
    s, r_gy = sp.symbols("s r_gy", positive=True)
    theta = s / r_gy
    radius = r_gy / sp.sqrt((a1 * sp.cos(theta)) ** 2 + (b1 * sp.sin(theta)) ** 2)
    # base along the x axis, outward normal +y (theta0 = pi/2); eq (12) turns the point counterclockwise with
    # theta, which is rolling towards -x: I2 = (-s, r) and P = I2 + r (cos(theta + theta0 + pi), sin(...))
    center = sp.Matrix([-s, radius])
    point = center + radius * sp.Matrix([sp.cos(theta + sp.pi / 2 + sp.pi), sp.sin(theta + sp.pi / 2 + sp.pi)])
    along, normal = (sp.simplify(sp.limit(sp.diff(c, s), s, 0)) for c in point)
    return -along, normal


def shaper_contact(alpha, rolled, cutter_radius, side):
    """(X - M2) in (T, n) of the flank point a pinion cutter of pitch radius ``cutter_radius`` generates while the
    involute's pitch point lies ``rolled`` = s_f - s along the pitch circle from the contact (module docstring);
    ``side`` +1 for the flank on the low-arc side of a gear tooth, -1 for the other. Also the cutter's roll
    parameter t there and the envelope condition's residual (zero)."""
    base = cutter_radius * sp.cos(alpha)
    sense = -side                                   # the cutter involute unwinds counterclockwise for side -1
    involute_function = sp.tan(alpha) - alpha
    beta = -sp.pi / 2 + rolled / cutter_radius - sense * involute_function   # pitch point rolled along from M2
    # the root of r_j sin(beta + sense t) + r_b = 0 near the pitch point
    t = sense * (-sp.pi / 2 + sense * alpha - beta)
    angle = beta + sense * t
    involute = base * sp.Matrix([sp.cos(angle) + sense * t * sp.sin(angle), sp.sin(angle) - sense * t * sp.cos(angle)])
    point = sp.Matrix([0, cutter_radius]) + involute
    residual = cutter_radius * sp.sin(angle) + base
    return sp.simplify(sp.expand_trig(point)), sp.simplify(t), sp.simplify(sp.expand_trig(residual))


def shaper_reach(alpha, cutter_radius, tip_radius, lowest_radius):
    """(low, high) of q = -side (s_f - s) over which the cutter's involute, from ``lowest_radius`` to ``tip_radius``,
    generates the flank: q < 0 below the pitch curve, q > 0 above it."""
    base = cutter_radius * sp.cos(alpha)
    # sqrt((radius / base)^2 - 1) as a product, so that the base circle itself (radius == base, the lowest radius of a
    # cutter with many teeth) gives an exact 0 in floating point, not the square root of a rounding below it
    roll = [sp.sqrt((radius - base) * (radius + base)) / base for radius in (tip_radius, lowest_radius)]
    # tan written as sin / cos: the printer maps sines and cosines only
    return tuple(cutter_radius * (sp.sin(alpha) / sp.cos(alpha) - t) for t in roll)


def _variable_involute() -> list[Derived]:
    alpha, rolled, side = (symbol_group(name, 1)[0] for name in ("pressure_angle", "rolled", "side"))
    cutter, tip, lowest = (symbol_group(name, 1)[0] for name in ("cutter_radius", "tip_radius", "lowest_radius"))
    point, _, _ = shaper_contact(alpha, rolled, sp.Symbol("r_j", positive=True), -1)
    along, normal = point                           # side -1; the side +1 flank is its mirror image in n
    return [
        Derived(name="variable_involute",
                doc=("Flank point minus the contact point, in the contact's (T, n), of the variable involute "
                     "(the cusp-pitch-curve paper, eq 1-6) whose pitch point lies rolled = s_f - s ahead; side +1 on a "
                     "tooth's low-arc side."),
                inputs=(("pressure_angle", (alpha,)), ("rolled", (rolled,)), ("side", (side,))),
                outputs=(("offset", (along, -side * normal)),)),
        Derived(name="shaper_reach",
                doc=("Range (low, high) of q = -side (s_f - s) over which a pinion cutter's involute, "
                     "from lowest_radius to tip_radius, generates the variable involute."),
                inputs=(("pressure_angle", (alpha,)), ("cutter_radius", (cutter,)), ("tip_radius", (tip,)),
                        ("lowest_radius", (lowest,))),
                outputs=(("reach", shaper_reach(alpha, cutter, tip, lowest)),)),
    ]


def _cycloid() -> Derived:
    base, angle = symbol_group("base", 2), symbol_group("tangent_angle", 1)[0]
    radius, theta, side = (symbol_group(name, 1)[0] for name in ("radius", "theta", "side"))
    alpha, zone, corner = (symbol_group(name, 1)[0] for name in ("pressure_angle", "zone", "corner_angle"))
    theta0, r, cusp, joint, over_corner = incomplete_cycloid(alpha, zone, corner)
    return [
        Derived(name="cycloid_trace",
                doc=("Point of a circle rolling outside the pitch curve (the cusp-pitch-curve paper, eq 9-12, "
                     "a1 = b1 = 1) at a base point and tangent angle."),
                inputs=(("base", base), ("tangent_angle", (angle,)), ("radius", (radius,)), ("theta", (theta,)),
                        ("side", (side,))),
                outputs=(("point", tuple(cycloid_trace(*base, angle, radius, theta, side))),)),
        Derived(name="incomplete_cycloid",
                doc=("Start angle, rolling radius, cusp offset from A, joint height and height over the corner of the "
                     "arch going on from a straight flank leaning alpha, rolling a zone S from A to the corner, where "
                     "its circle has turned corner_angle."),
                inputs=(("pressure_angle", (alpha,)), ("zone", (zone,)), ("corner_angle", (corner,))),
                outputs=(("start_angle", (theta0,)), ("radius", (r,)), ("cusp", (cusp,)), ("joint_height", (joint,)),
                         ("corner_height", (over_corner,)))),
    ]


def derive() -> list[Derived]:
    return [_curvature_center(), _corner_angles(), *_cycloid(), *_variable_involute()]

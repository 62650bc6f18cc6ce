"""Disc cams with a roller follower: motion laws, the roller centre, the pitch curve, the profile,
the pressure angle and the curvature (Wang et al. 2025, section 4, uses a swinging roller follower with
simple harmonic motion).

Frames. The cam turns about the origin by the cam angle theta (rad) in the sense sigma (+1
counterclockwise, -1 clockwise). A point that stands still on the ground at c is, in the cam's own
frame, at R(-sigma theta) c: inverting the motion, the roller centre c(theta) traces the pitch
curve p(theta) = R(-sigma theta) c(theta) on the cam.

- Motion laws. Each law is a rise y(tau) of unit lift over tau in [0, 1], derived from what
  defines it, not typed in:
    harmonic              y'' = A cos(pi tau), y(0) = y'(0) = 0, y(1) = 1;
    cycloidal             y'' = A sin(2 pi tau), same ends;
    polynomial 3-4-5      the quintic with y, y', y'' = (0, 0, 0) at tau = 0 and (1, 0, 0) at tau = 1;
    modified trapezoid    y'' a quarter sine up over 1/8, flat over 1/4, a half cosine down over 1/4,
                          flat over 1/4, a quarter sine back to zero over 1/8; same ends.
  A segment of angle beta and signed lift h (negative for a return) that starts at level s0 moves the
  follower by s = s0 + h y(phi / beta), phi the cam angle into the segment; velocity, acceleration and
  jerk are its derivatives with respect to phi (per radian of cam).
- Roller centre on the ground. Translating: c = (e, s_base + s), moving along w = (0, 1) at offset e,
  with s_base = sqrt((R_b + R_r)^2 - e^2) computed by the caller (no square root here). Oscillating:
  c = A + L (cos b, sin b) with b = b0 + kappa psi, moving along w = kappa (-sin b, cos b).
- Tangent of the pitch curve: dp/dtheta = R(-sigma theta) T with T = c' - sigma J c (J the quarter
  turn counterclockwise), the roller centre's velocity relative to the cam per radian of cam; and
  d2p/dtheta2 = R(-sigma theta) (T' - sigma J T).
- Pressure angle: between the pitch curve's normal (the line of the contact force) and the roller
  centre's direction of motion w, alpha = atan2(T . w, sigma T x w); for a translating follower with
  offset e this is tan(alpha) = (s' - sigma e) / (s_base + s).
- Curvature radius, positive where the pitch curve is convex: the curve runs clockwise on the cam
  when the cam turns counterclockwise, so rho = -sigma |T|^3 / (T x (T' - sigma J T)).
- Profile: the pitch curve offset towards the cam by the roller radius, q = p - R_r sigma J t with t
  the unit tangent (sigma J t is the outward normal); its curvature radius is rho - R_r.
- Flat-faced translating follower: its face, square to the motion (0, 1), stands at height
  h = R_b + s. In the cam frame the face is the line n . q = h with n = R(-sigma theta) (0, 1); the
  profile is the envelope of these lines, solved from n . q = h and d/dtheta (n . q - h) = 0. Its
  curvature radius is q' . n' / |n'|^2 (q' is parallel to n'), and the contact point's offset along
  the face, on the ground, tells the face width needed.
"""
from __future__ import annotations

import sympy as sp

from derivations.planar import cross
from derivations.spec import Derived, symbol_group

tau = sp.Symbol("tau", real=True)
LAWS = ("harmonic", "cycloidal", "polynomial_345", "modified_trapezoid")
# The printer has no name for pi: it enters the generated code as a double.
PI = sp.Float(sp.pi, 20)


def _integrate_acceleration(pieces, breaks):
    """Displacement pieces y_k(tau) of unit lift from acceleration pieces a_k(tau, A) on [breaks[k],
    breaks[k+1]], with y and y' continuous, y(0) = y'(0) = 0, and A fixed by y(1) = 1."""
    amplitude = sp.Symbol("A")
    velocity_start, displacement_start, displacements = 0, 0, []
    for shape, (low, high) in zip(pieces, zip(breaks[:-1], breaks[1:], strict=True), strict=True):
        x = sp.Symbol("x", real=True)
        velocity = velocity_start + sp.integrate(amplitude * shape.subs(tau, x), (x, low, tau))
        displacement = displacement_start + sp.integrate(velocity.subs(tau, x), (x, low, tau))
        displacements.append(displacement)
        velocity_start, displacement_start = velocity.subs(tau, high), displacement.subs(tau, high)
    (value,) = sp.solve(sp.Eq(displacement_start, 1), amplitude)
    return [sp.expand(d.subs(amplitude, value)) for d in displacements]


def _piecewise(displacements, breaks):
    if len(displacements) == 1:
        return displacements[0]
    return sp.Piecewise(*[(d, tau < b) for d, b in zip(displacements[:-1], breaks[1:-1], strict=True)],
                        (displacements[-1], True))


def unit_rise(law: str):
    """y(tau) of ``law``: a rise of unit lift over tau in [0, 1] (a Piecewise for the modified trapezoid)."""
    if law == "harmonic":
        return _integrate_acceleration([sp.cos(sp.pi * tau)], [0, 1])[0]
    if law == "cycloidal":
        return _integrate_acceleration([sp.sin(2 * sp.pi * tau)], [0, 1])[0]
    if law == "polynomial_345":
        coefficients = sp.symbols("k0:6")
        y = sum(k * tau**n for n, k in enumerate(coefficients))
        ends = [y, sp.diff(y, tau), sp.diff(y, tau, 2)]
        conditions = [e.subs(tau, 0) for e in ends] + [ends[0].subs(tau, 1) - 1] + [e.subs(tau, 1) for e in ends[1:]]
        return sp.expand(y.subs(sp.solve(conditions, coefficients)))
    if law == "modified_trapezoid":
        eighth = sp.Rational(1, 8)
        breaks = [0, eighth, 3 * eighth, 5 * eighth, 7 * eighth, 1]
        shapes = [sp.sin(4 * sp.pi * tau), sp.Integer(1), sp.cos(4 * sp.pi * (tau - 3 * eighth)), sp.Integer(-1),
                  -sp.sin(4 * sp.pi * (1 - tau))]
        return _piecewise(_integrate_acceleration(shapes, breaks), breaks)
    raise ValueError(f"no law {law}")


def segment_motion(law: str, angle, segment_angle, lift, start_level):
    """(s, ds/dphi, d2s/dphi2, d3s/dphi3) of a segment of ``law``, ``phi`` = ``angle`` into it."""
    s = start_level + lift * unit_rise(law).subs(tau, angle / segment_angle)
    return tuple(sp.diff(s, angle, order) if order else s for order in range(4))


def _with_float_pi(expr):
    return expr.subs(sp.pi, PI)


def _law(law: str) -> Derived:
    angle, segment_angle, lift, start_level = symbol_group("segment", 4)
    motion = segment_motion(law, angle, segment_angle, lift, start_level)
    return Derived(
        name=f"cam_law_{law}",
        doc=(f"{law.replace('_', ' ')} law: follower displacement, velocity, acceleration and jerk (per rad of cam) "
             "at angle phi into a segment of angle beta, signed lift h, starting level s0; "
             "segment = (phi, beta, h, s0)."),
        inputs=(("segment", (angle, segment_angle, lift, start_level)),),
        outputs=(("motion", tuple(_with_float_pi(m) for m in motion)),),
    )


def _quarter_turn(v):
    return sp.Matrix([-v[1], v[0]])


def translating_center(offset, base_height, s, ds, d2s):
    """Roller centre, its first and second cam-angle derivatives and direction of motion (translating)."""
    return (sp.Matrix([offset, base_height + s]), sp.Matrix([0, ds]), sp.Matrix([0, d2s]), sp.Matrix([0, 1]))


def oscillating_center(pivot, arm, start_angle, sense, psi, dpsi, d2psi):
    """The same for an arm of length ``arm`` about ``pivot`` at angle ``start_angle + sense psi``."""
    b = start_angle + sense * psi
    radial, across = sp.Matrix([sp.cos(b), sp.sin(b)]), sp.Matrix([-sp.sin(b), sp.cos(b)])
    center = sp.Matrix(pivot) + arm * radial
    rate = arm * sense * dpsi * across
    # sense**2 = 1: d/dtheta of sense dpsi across is sense d2psi across - dpsi**2 radial
    accel = arm * (sense * d2psi * across - dpsi**2 * radial)
    return center, rate, accel, sense * across


def pitch_and_profile(theta, sense, roller, center, rate, accel, direction):
    """Pitch point, profile point, pressure angle, curvature radii of pitch curve and profile."""
    back = sp.Matrix([[sp.cos(theta), sp.sin(theta)], [-sp.sin(theta), sp.cos(theta)]])   # R(-theta)
    turn = back.subs(theta, sense * theta)
    tangent = rate - sense * _quarter_turn(center)
    bend = accel - sense * _quarter_turn(rate) - sense * _quarter_turn(tangent)
    speed = sp.sqrt(tangent.dot(tangent))
    pitch = turn * center
    outward = sense * _quarter_turn(turn * tangent) / speed
    profile = pitch - roller * outward
    pressure = sp.atan2(tangent.dot(direction), sense * cross(tangent, direction))
    radius = -sense * speed**3 / cross(tangent, bend)
    return pitch, profile, pressure, radius, radius - roller


def _pitch() -> Derived:
    theta, sense, roller = symbol_group("cam", 3)
    center, rate, accel, direction = (sp.Matrix(symbol_group(name, 2)) for name in
                                      ("center", "center_rate", "center_accel", "direction"))
    pitch, profile, pressure, radius, profile_radius = pitch_and_profile(theta, sense, roller, center, rate, accel,
                                                                        direction)
    return Derived(
        name="cam_pitch_profile",
        doc=("Pitch point and profile point in the cam frame, pressure angle (rad) and curvature radii (mm, convex "
             "positive) of pitch curve and profile; cam = (theta, sigma, roller radius), the roller centre on the "
             "ground with its first and second theta-derivatives and its direction of motion."),
        inputs=(("cam", (theta, sense, roller)), ("center", tuple(center)), ("center_rate", tuple(rate)),
                ("center_accel", tuple(accel)), ("direction", tuple(direction))),
        outputs=(("pitch", tuple(pitch)), ("profile", tuple(profile)), ("pressure_angle", (pressure,)),
                 ("curvature_radius", (radius, profile_radius))),
    )


def _followers() -> list[Derived]:
    offset, base_height = symbol_group("translating", 2)
    motion = symbol_group("motion", 3)
    pivot_x, pivot_y, arm, start_angle, sense = symbol_group("oscillating", 5)
    groups = (("center", "roller centre (mm)"), ("center_rate", "d/dtheta"), ("center_accel", "d2/dtheta2"),
              ("direction", "unit direction of motion"))
    translating = translating_center(offset, base_height, *motion)
    oscillating = oscillating_center((pivot_x, pivot_y), arm, start_angle, sense, *motion)
    return [
        Derived(name="cam_translating_roller",
                doc=("Roller centre of a translating follower, its theta-derivatives and direction of motion; "
                     "translating = (offset e, s_base), motion = (s, s', s'')."),
                inputs=(("translating", (offset, base_height)), ("motion", motion)),
                outputs=tuple((name, tuple(v)) for (name, _), v in zip(groups, translating, strict=True))),
        Derived(name="cam_oscillating_roller",
                doc=("Roller centre of an oscillating follower, its theta-derivatives and direction of motion; "
                     "oscillating = (pivot x, pivot y, arm L, start angle b0, sense kappa), "
                     "motion = (psi, psi', psi'')."),
                inputs=(("oscillating", (pivot_x, pivot_y, arm, start_angle, sense)), ("motion", motion)),
                outputs=tuple((name, tuple(sp.expand(e) for e in v))
                              for (name, _), v in zip(groups, oscillating, strict=True))),
    ]


def flat_faced_profile(theta, sense, base_radius, s, ds, d2s):
    """Profile point (cam frame), its curvature radius and the contact's offset along the face (ground)."""
    q = sp.Matrix(sp.symbols("q_x q_y", real=True))
    normal = sp.Matrix([-sp.sin(-sense * theta), sp.cos(-sense * theta)])     # R(-sigma theta) (0, 1)
    height, rate = base_radius + s, ds
    solution = sp.solve([normal.dot(q) - height, sp.diff(normal, theta).dot(q) - rate], list(q), dict=True)[0]
    point = sp.Matrix([sp.simplify(solution[q[0]]), sp.simplify(solution[q[1]])])
    # d/dtheta with s' and s'' for the derivatives of s and s'
    speed = sp.diff(point, theta) + sp.diff(point, s) * ds + sp.diff(point, ds) * d2s
    turning = sp.diff(normal, theta)
    radius = sp.simplify(speed.dot(turning) / turning.dot(turning))
    back = sp.Matrix([[sp.cos(sense * theta), -sp.sin(sense * theta)], [sp.sin(sense * theta), sp.cos(sense * theta)]])
    contact = sp.simplify((back * point)[0])
    return point, radius, contact


def _flat_faced() -> Derived:
    theta, sense, base = symbol_group("cam", 3)
    motion = symbol_group("motion", 3)
    point, radius, contact = flat_faced_profile(theta, sense, base, *motion)
    return Derived(
        name="cam_flat_faced",
        doc=("Flat-faced translating follower: profile point in the cam frame, its curvature radius (mm, convex "
             "positive) and the contact's offset along the face on the ground; cam = (theta, sigma, base radius), "
             "motion = (s, s', s'')."),
        inputs=(("cam", (theta, sense, base)), ("motion", motion)),
        outputs=(("profile", tuple(point)), ("curvature_radius", (radius,)), ("face_offset", (contact,))),
    )


def derive() -> list[Derived]:
    return [*(_law(law) for law in LAWS), *_followers(), _pitch(), _flat_faced()]

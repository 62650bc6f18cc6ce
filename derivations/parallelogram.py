"""The onion transplanter of the onion-transplanter paper: denatured limacon gear pair driving a parallelogram
(eq 3-4, 16-18).

Gear pair. Driver r1(phi1) = l + b cos(u), with u = m11 phi1 on 0 <= phi1 <= pi/m11 and
u = m12 (2 pi - phi1) beyond (eq 3). Pure rolling at center distance a gives
dphi2/dphi1 = r1 / (a - r1) (eq 4), and in u, with p = a - l,
    r1 / (a - r1) = a / (p - b cos u) - 1.
For p > b the Weierstrass substitution gives the antiderivative
    F(u) = 2 a / sqrt(p^2 - b^2) atan2(sqrt(p + b) sin(u/2), sqrt(p - b) cos(u/2)) - u,
continuous on 0 <= u <= pi (dF/du = integrand: ``driven_antiderivative_residual``). Hence
    phi2 = F(m11 phi1) / m11                                     (first half),
    phi2 = F(pi) / m11 + (F(m12 (2 pi - pi/m11)) - F(m12 (2 pi - phi1))) / m12   (second half).
With eq (2) (1/m11 + 1/m12 = 2) a whole turn gives 2 (pi a / sqrt(p^2 - b^2) - pi), the plain
limacon's, so closure does not involve m11 and its center distance is the gear library's
``limacon_center_distance`` (order ratio 1). phi2 is homogeneous of degree 0 in (a, b, l):
the kinematics sees b/l and a/l only (``driven_angle_scale_derivative`` is 0).

Parallelogram (eq 16-18). Crank O2A (length l1) turns with the driven gear; the coupler AB
(l2 = O2D) keeps the frame's direction, here horizontal, so every coupler point moves as A
does. With the crank angle theta = phase + sense phi2 (counterclockwise from +x, sense = +1
or -1) and the crank pivot O2 = (x, y):
    A = O2 + l1 (cos theta, sin theta),    E = A + (l2 + l5, -l6).
Eq (18) prints X_E = X_A + (l2 + l3); l5 (BC, a design variable that appears nowhere else)
is read for l3 there. Neither reading changes an objective: l2, l5, l6 and O2 enter E only as
a constant offset (``translation_parameter_derivatives`` of the velocity and acceleration are 0).

Field motion. The driver turns at constant omega1 (phi1 = omega1 t) and the machine moves at
forward_velocity along x (signed), so X_field = X_E + forward_velocity t and, by the chain rule,
    V = omega1 dE/dphi1 + (forward_velocity, 0),   acc = omega1^2 d2E/dphi1^2
(exact derivatives; the paper used central differences).
"""
from __future__ import annotations

import math

import sympy as sp

from derivations.spec import Derived, symbol_group

PI = sp.Float(math.pi, 17)


def driven_antiderivative(u, center_distance, base, amplitude):
    """F(u): antiderivative in u of r1 / (a - r1) for r1 = l + b cos(u), on 0 <= u <= pi."""
    p = center_distance - base
    root = sp.sqrt(p**2 - amplitude**2)
    return 2 * center_distance / root * sp.atan2(sp.sqrt(p + amplitude) * sp.sin(u / 2),
                                                sp.sqrt(p - amplitude) * sp.cos(u / 2)) - u


def driven_antiderivative_residual(u, center_distance, base, amplitude):
    """dF/du minus the integrand r1 / (a - r1): zero (checked in the tests)."""
    r1 = base + amplitude * sp.cos(u)
    return sp.diff(driven_antiderivative(u, center_distance, base, amplitude), u) - r1 / (center_distance - r1)


def driven_angle(phi1, center_distance, base, amplitude, m11, m12, pi=PI):
    """phi2(phi1) over one driver turn, 0 <= phi1 <= 2 pi, of the pair of eq (3)-(4)."""
    joint = pi / m11

    def F(u):
        return driven_antiderivative(u, center_distance, base, amplitude)

    p = center_distance - base
    half_turn = pi * center_distance / sp.sqrt(p**2 - amplitude**2) - pi      # F(pi): atan2(., 0) = pi/2
    second = half_turn / m11 + (F(m12 * (2 * pi - joint)) - F(m12 * (2 * pi - phi1))) / m12
    return sp.Piecewise((F(m11 * phi1) / m11, m11 * phi1 <= pi), (second, True))


def driver_radius(phi1, base, amplitude, m11, m12, pi=PI):
    """Eq (3): r1(phi1) of the denatured limacon."""
    return sp.Piecewise((base + amplitude * sp.cos(m11 * phi1), m11 * phi1 <= pi),
                        (base + amplitude * sp.cos(m12 * (2 * pi - phi1)), True))


def crank_pin(phi1, gear, pivot, crank_length, phase, sense):
    """A of eq (17): the crank pin at crank angle phase + sense phi2 (counterclockwise from +x)."""
    theta = phase + sense * driven_angle(phi1, *gear)
    return sp.Matrix([pivot[0] + crank_length * sp.cos(theta), pivot[1] + crank_length * sp.sin(theta)])


def tip_relative(phi1, gear, pivot, links, phase, sense):
    """E of eq (18) in the machine's frame: A + (l2 + l5, -l6)."""
    l1, l2, l5, l6 = links
    return crank_pin(phi1, gear, pivot, l1, phase, sense) + sp.Matrix([l2 + l5, -l6])


def tip_field(phi1, time, gear, pivot, links, phase, sense, driver_speed, forward_velocity):
    """(position, velocity, acceleration) of E in the field frame (mm, mm/s, mm/s^2)."""
    relative = tip_relative(phi1, gear, pivot, links, phase, sense)
    slope = relative.diff(phi1)
    position = relative + sp.Matrix([forward_velocity * time, 0])
    velocity = driver_speed * slope + sp.Matrix([forward_velocity, 0])
    acceleration = driver_speed**2 * slope.diff(phi1)
    return position, velocity, acceleration


def translation_parameter_derivatives(phi1, gear, pivot, links, phase, sense, driver_speed, forward_velocity):
    """Jacobian of E's velocity and acceleration with respect to l2, l5, l6 and the pivot: all zero."""
    time = sp.Symbol("time", real=True)
    _, velocity, acceleration = tip_field(phi1, time, gear, pivot, links, phase, sense, driver_speed, forward_velocity)
    return sp.Matrix([*velocity, *acceleration]).jacobian(sp.Matrix([*links[1:], *pivot]))


def driven_angle_scale_derivative(phi1, gear):
    """Euler's test of degree-0 homogeneity in (a, l, b): a dphi2/da + l dphi2/dl + b dphi2/db."""
    a, base, amplitude = gear[:3]
    phi2 = driven_angle(phi1, *gear)
    return sum(x * sp.diff(phi2, x) for x in (a, base, amplitude))


def derive() -> list[Derived]:
    angle, time = symbol_group("driver_angle", 1), symbol_group("time", 1)
    pitch = symbol_group("pitch", 4)              # base l, amplitude b, m11, m12
    a = symbol_group("center_distance", 1)
    links = symbol_group("links", 4)              # l1, l2, l5, l6
    crank = symbol_group("crank", 4)              # phase, sense, pivot x, pivot y
    motion = symbol_group("motion", 2)            # omega1, forward velocity
    gear = (a[0], *pitch)
    phase, sense, pivot = crank[0], crank[1], crank[2:]
    position, velocity, acceleration = tip_field(angle[0], time[0], gear, pivot, links, phase, sense, *motion)
    pin = crank_pin(angle[0], gear, pivot, links[0], phase, sense)
    relative = tip_relative(angle[0], gear, pivot, links, phase, sense)
    r = driver_radius(angle[0], *pitch)
    return [
        Derived(name="limacon_driven_angle",
                doc=("Eq (4) in closed form: driven rotation phi2 at driver angle phi1 in [0, 2 pi] for the "
                     "denatured limacon of eq (3) (pitch = l, b, m11, m12) at center distance a; and r1."),
                inputs=(("driver_angle", angle), ("pitch", pitch), ("center_distance", a)),
                outputs=(("driven_angle", (driven_angle(angle[0], *gear),)), ("driver_radius", (r,)))),
        Derived(name="parallelogram_tip",
                doc=("Eq (16)-(18) with forward motion: crank pin A (machine frame), planting point E (field "
                     "frame), its velocity and acceleration (exact), at driver angle phi1 in [0, 2 pi] and time t; "
                     "links = l1, l2, l5, l6; crank = phase, sense, pivot; motion = omega1, forward velocity."),
                inputs=(("driver_angle", angle), ("time", time), ("pitch", pitch), ("center_distance", a),
                        ("links", links), ("crank", crank), ("motion", motion)),
                outputs=(("crank_pin", tuple(pin)), ("tip", tuple(position)), ("velocity", tuple(velocity)),
                         ("acceleration", tuple(acceleration)))),
        Derived(name="parallelogram_position",
                doc=("E of eq (18) in the machine's frame (no forward motion, no derivatives): the cheap "
                     "evaluation for dense grids; same inputs as parallelogram_tip without time and motion."),
                inputs=(("driver_angle", angle), ("pitch", pitch), ("center_distance", a), ("links", links),
                        ("crank", crank)),
                outputs=(("tip", tuple(relative)),)),
    ]

"""The arm's rates on the spline segments where the path touches a reach circle, without cancellation.

Near a touch (the arm straight at |P| = s + l, or folded at |P| = |s - l|) the closed-form rates divide
by the sine of the elbow angle, itself the square root of a difference that cancels: in double precision
the elbow carries ~1e-8 rad of rounding, and chi''' within 1e-4 rad of the touch is off by orders of
magnitude (the rice example: 5e4 where the motion has -0.91), which the gears read as hollows.

On a segment of the cubic path P(tau), tau = x - x* from the touch x*, |P|^2 is a polynomial; its
Taylor coefficients about x* of order 0 and 1 are the circle's radius squared and zero (the path
touches there, which is what a touch means), so the small factor of the elbow's product is
tau^2 H(tau) / (|P| + R) with H a polynomial of the coefficients of order >= 2, R the circle's radius.
The elbow is then atan2(-b tau sqrt(H rest / (|P| + R)), s^2 + |P|^2 - l^2) (b the branch before the
touch: the branch switch makes the signed elbow smooth through the touch), and theta, psi and their
derivatives to the third follow by automatic differentiation of that expression, which has no 0 / 0.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np
from numpy.polynomial import Polynomial

from transplanter.geometry.closed_trajectory import ClosedTrajectory
from transplanter.geometry.planar import TWO_PI

#: A touch within this fraction of a segment of a spline knot is at the knot: both segments meeting there
#: touch the circle (the path's third derivative jumps there, so each side has its own polynomial).
AT_KNOT = 1e-9


@dataclass(frozen=True)
class TouchSegment:
    """One spline segment containing a touch: x in [start, start + width) uses ``rates``."""

    start: float
    width: float
    touch: float                 # x* (on this segment's side of the period)
    rates: ca.Function           # tau -> theta', psi', theta'', psi'', theta''', psi''' (rad per unit x)

    def evaluate(self, x: np.ndarray) -> np.ndarray:
        """(6, len(x)): theta^(k), psi^(k) for k = 1..3 at x on this segment."""
        return np.asarray(self.rates(np.reshape(x - self.touch, (1, -1)))).reshape(6, len(x))


def _segment_rates(polynomials: np.ndarray, t_touch: float, scale: float, lengths: tuple[float, float],
                   circle: str, branch_before: int) -> ca.Function:
    """The rates of one segment (polynomials (4, 2) in t; t = t_touch + scale tau)."""
    carrier, arm = lengths
    shift = Polynomial([t_touch, scale])
    x_poly, y_poly = (Polynomial(polynomials[:, j])(shift) for j in (0, 1))
    b = (x_poly**2 + y_poly**2).coef
    radius = carrier + arm if circle == "outer" else abs(carrier - arm)
    tail = Polynomial(b[2:]) if circle == "inner" else -Polynomial(b[2:])
    tau = ca.SX.sym("tau")

    def value(poly: Polynomial) -> ca.SX:
        total = ca.SX(0)
        for c in reversed(poly.coef.tolist()):      # Horner
            total = total * tau + c
        return total

    px, py = value(x_poly), value(y_poly)
    r = ca.sqrt(px**2 + py**2)
    factors = [arm - carrier + r, arm + carrier - r, r + carrier - arm, r + carrier + arm]
    small = 1 if circle == "outer" else (2 if arm >= carrier else 0)
    rest = factors[(small + 1) % 4] * factors[(small + 2) % 4] * factors[(small + 3) % 4]
    elbow = ca.atan2(-branch_before * tau * ca.sqrt(value(tail) * rest / (r + radius)), carrier**2 + r**2 - arm**2)
    theta = ca.atan2(py, px) + elbow
    psi = ca.atan2(py - carrier * ca.sin(theta), px - carrier * ca.cos(theta))
    derivatives: list[ca.SX] = []
    current = [theta, psi]
    for _ in range(3):
        current = [ca.jacobian(v, tau) for v in current]
        derivatives.extend(current)
    return ca.Function("touch_rates", [tau], [ca.vertcat(*derivatives)], {"cse": True})


def touch_segments(trajectory: ClosedTrajectory, lengths: tuple[float, float], touches, start_branch: int
                   ) -> tuple[TouchSegment, ...]:
    """The segments containing each touch (two for a touch at a knot), with their rate functions."""
    count = trajectory.count
    scale = count / TWO_PI
    polynomials = trajectory.segment_polynomials()
    found = []
    for index, touch in enumerate(touches):
        branch_before = start_branch * (-1) ** index
        position = touch.parameter * scale
        nearest = round(position)
        at_knot = abs(position - nearest) <= AT_KNOT
        segments = ((nearest - 1, 1.0), (nearest, 0.0)) if at_knot else ((int(np.floor(position)), None),)
        for k, t_touch in segments:
            t = position - k if t_touch is None else t_touch
            rates = _segment_rates(polynomials[k % count], t, scale, lengths, touch.circle, branch_before)
            start = (k % count) / scale
            found.append(TouchSegment(start, 1 / scale, start + t / scale, rates))
    return tuple(found)

"""The arm's rates where the path touches a reach circle, against a 50-digit evaluation of the same motion.

The reference rebuilds the tip from the control points (the centered cubic B-spline), takes the arm lengths
from the path's exact farthest and nearest distances (so the path touches both circles), solves the
two-link inverse kinematics and differentiates it numerically, all in 50 digits; the chain rule gives
chi', chi'', chi''' in the carrier turn. Near a touch the closed form in double precision misses chi''' by
orders of magnitude (the hollows the gears read); the touch segments must agree to 1e-7.
"""
from __future__ import annotations

from pathlib import Path

import mpmath as mp
import numpy as np
import pytest

from transplanter.reverse.arm_inverse import solve_arm
from transplanter.reverse.carrier_frame_motion import CarrierFrameMotion
from transplanter.reverse.pitch_corners import pitch_corners
from transplanter.reverse.problem import load_problem
from transplanter.reverse.synthesis import build_trajectory
from transplanter.trains.planetary import design_train

RICE = Path(__file__).parents[2] / "examples" / "rice_hoe_reverse.toml"


class ExactMotion:
    def __init__(self, control: np.ndarray, direction: int):
        self.control = [[mp.mpf(float(v)) for v in row] for row in control]
        self.direction = direction
        farthest = mp.sqrt(self.square(mp.findroot(lambda x: mp.diff(self.square, x), mp.pi)))
        nearest = mp.sqrt(self.square(mp.mpf(0)))
        self.lengths = ((farthest - nearest) / 2, (farthest + nearest) / 2)   # the rice-transplanter paper eq 1-2

    def square(self, x):
        return sum(v**2 for v in self.tip(x))

    def tip(self, x):
        count = len(self.control)
        u0 = x * count / (2 * mp.pi)
        point = [mp.mpf(0), mp.mpf(0)]
        for i, q in enumerate(self.control):
            u = u0 - i
            a = abs(u - count * mp.floor(u / count + mp.mpf(1) / 2))
            b = mp.mpf(2) / 3 - a**2 + a**3 / 2 if a < 1 else ((2 - a)**3 / 6 if a < 2 else 0)
            point = [p + v * b for p, v in zip(point, q, strict=True)]
        return point

    def angles(self, x, branch):
        carrier, arm = self.lengths
        px, py = self.tip(x)
        r = mp.sqrt(px**2 + py**2)
        product = (arm - carrier + r) * (arm + carrier - r) * (r + carrier - arm) * (r + carrier + arm)
        theta = mp.atan2(py, px) + branch * mp.atan2(mp.sqrt(max(product, 0)), carrier**2 + r**2 - arm**2)
        return theta, mp.atan2(py - carrier * mp.sin(theta), px - carrier * mp.cos(theta)) - theta

    def relative_rates(self, x, branch):
        """chi', chi'', chi''' in the carrier turn."""
        c1, c2, c3 = (self.direction * mp.diff(lambda t: self.angles(t, branch)[0], x, k) for k in (1, 2, 3))
        h1, h2, h3 = (-self.direction * mp.diff(lambda t: self.angles(t, branch)[1], x, k) for k in (1, 2, 3))
        return (h1 / c1, (h2 * c1 - h1 * c2) / c1**3,
                ((h3 * c1 - h1 * c3) * c1 - 3 * c2 * (h2 * c1 - h1 * c2)) / c1**5)


@pytest.fixture(scope="module")
def motions():
    mp.mp.dps = 50
    problem = load_problem(RICE)
    trajectory = build_trajectory(problem)
    exact = ExactMotion(trajectory.control, problem.direction)
    radii = [e.radius for e in trajectory.radial_extremes()]
    lengths = ((max(radii) - min(radii)) / 2, (max(radii) + min(radii)) / 2)
    return solve_arm(trajectory, *lengths, problem.direction, 1), exact


@pytest.mark.parametrize("offset", [-1e-3, -1e-5, -1e-6, 1e-6, 1e-5, 1e-3])
@pytest.mark.parametrize("circle", ["outer", "inner"])
def test_rates_near_a_touch_match_the_exact_motion(motions, circle, offset):
    motion, exact = motions
    touch = next(t for t in motion.touches if t.circle == circle)
    x = float(np.mod(touch.parameter + offset, 2 * np.pi))
    (c1, c2, c3), (h1, h2, h3) = (np.ravel(v) for v in motion.path_rates(np.array([x])))
    rates = (h1 / c1, (h2 * c1 - h1 * c2) / c1**3, ((h3 * c1 - h1 * c3) * c1 - 3 * c2 * (h2 * c1 - h1 * c2)) / c1**5)
    expected = exact.relative_rates(mp.mpf(x), float(motion.branch(np.array([x]))[0]))
    scale = [abs(float(v)) for v in exact.relative_rates(mp.mpf(float(touch.parameter) - 0.1), 1.0)]
    for order, (value, reference, size) in enumerate(zip(rates, expected, scale, strict=True), 1):
        assert abs(float(value) - float(reference)) <= 1e-7 * max(abs(float(reference)), size), order


def test_sun_corner_at_the_nearest_point_follows_the_exact_motion(motions):
    """The nearest point lies on a spline knot: chi'' jumps there, and the sun's pitch curve r = a / (1 + I1),
    I1 = chi'^(-1/2) / k, turns its tangent by the jump of atan2(r, dr/dc)."""
    motion, exact = motions
    train = design_train(CarrierFrameMotion(motion), (40.0, 50.0))
    touch = next(t for t in motion.touches if t.circle == "inner")
    corner = next(c for c in pitch_corners(motion, train) if c.gear == "sun" and c.corner)
    a, k = 40.0, train.correction
    mu = []
    for side in (-1e-8, 1e-8):       # a stencil of mp.diff clear of the knot at the touch
        x = mp.mpf(float(touch.parameter)) + side if side < 0 else mp.mpf(side)
        slope, bend, _ = exact.relative_rates(x, float(motion.branch(np.array([float(x)]))[0]))
        ratio = slope ** mp.mpf(-0.5) / k
        r = a / (1 + ratio)
        mu.append(mp.atan2(r, a * slope ** mp.mpf(-1.5) * bend / (2 * k) / (1 + ratio) ** 2))
    assert corner.tangent_turn == pytest.approx(float(mu[1] - mu[0]), rel=1e-5)
    assert corner.hollow and not any(c.corner for c in pitch_corners(motion, train) if c.carrier_turn > 1)

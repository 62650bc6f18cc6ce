"""Inverse kinematics of the planetary arm along a closed path (the reverse-gear-design paper;
the rice-transplanter paper eq 3-4).

The carrier (length s) turns about the pivot; the arm (length l) is fixed to the planet.
At each path point the generated ``two_link_inverse`` gives the carrier direction theta on a
branch (+1 approach, -1 retraction) and the arm direction psi. The two branches meet only
where the path touches the circles r = s + l (arm straight) or r = |s - l| (arm folded); a
path that meets a circle there touches it, and the branch switches at every touch, which is
the one continuation that keeps theta smooth (the rice-transplanter paper's lengths from Lmax and Lmin make the
path touch both circles, so the carrier turns once while the tip runs round a loop that
need not enclose the pivot).

Along the path parameter x, the carrier has turned c(x) = d (theta(x) - theta(0)) in the
rotation direction d (+1 counterclockwise) and the planet, against the carrier, chi(x) =
-d (gamma(x) - gamma(0)) with gamma = psi - theta: two external meshes turn the planet the
sun's way in the carrier frame; ``carrier_frame_motion`` turns this into chi(c), the relative
motion the gear train must produce (total ratio sun : planet = 1 / chi'(c)).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from transplanter._generated.planetary import two_link_inverse, two_link_rates
from transplanter.generated import numpy_twin
from transplanter.geometry.closed_trajectory import ClosedTrajectory, RadialExtreme
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.touch_rates import TouchSegment, touch_segments

_inverse = numpy_twin(two_link_inverse)
_rates = numpy_twin(two_link_rates)

#: An extreme of |P| within this fraction of the reach s + l of r = s + l or |s - l| touches the
#: circle (1e-6 mm on the rice path's 254 mm): relative, so a path in metres or micrometres behaves the same.
TOUCH_TOLERANCE = 4e-9
#: Within this distance (in x) of a touch, the angles are interpolated between the two sides (rates: ``touch_rates``).
TOUCH_LIMIT = 1e-5
#: Offsets (rad of carrier turn) of the extra breaks on either side of a touch.
TOUCH_GRADING = 1e-4 * 2.0 ** np.arange(11)
#: Reference samples per B-spline segment (unwrapping, first guesses, checks).
GRID_PER_SEGMENT = 128
BRANCH_NAMES = {1: "approach", -1: "retraction"}
DIRECTION_NAMES = {1: "counterclockwise", -1: "clockwise"}


@dataclass(frozen=True)
class Touch:
    parameter: float        # x of the touch
    circle: str             # "outer" (arm straight) or "inner" (arm folded)
    gap_mm: float           # circle radius minus |P| there (negative: just beyond reach)


@dataclass(frozen=True)
class ArmMotion:
    trajectory: ClosedTrajectory
    carrier_length: float
    arm_length: float
    direction: int                      # +1 counterclockwise carrier, -1 clockwise
    start_branch: int                   # branch at x = 0
    touches: tuple[Touch, ...]
    grid: np.ndarray = field(repr=False)
    theta_grid: np.ndarray = field(repr=False)     # unwrapped, with the value at 2 pi appended
    gamma_grid: np.ndarray = field(repr=False)

    @property
    def lengths(self) -> np.ndarray:
        return np.array([self.carrier_length, self.arm_length])

    def branch(self, x) -> np.ndarray:
        switches = np.array([t.parameter for t in self.touches])
        passed = np.sum(np.mod(np.asarray(x, float), TWO_PI)[..., None] > switches, axis=-1)
        return self.start_branch * (-1.0) ** passed

    def raw_angles(self, x) -> tuple[np.ndarray, np.ndarray]:
        point = np.moveaxis(self.trajectory.evaluate(x), -1, 0)
        theta, psi = _inverse(point, self.lengths[:, None], self.branch(x)[None])[0]
        return theta, psi

    def _unwrapped(self, x, raw, table):
        reference = np.interp(np.mod(x, TWO_PI), np.r_[self.grid, TWO_PI], table)
        return raw + TWO_PI * np.round((reference - raw) / TWO_PI)

    def _continuous(self, x):
        theta, psi = self.raw_angles(x)
        theta = self._unwrapped(x, theta, self.theta_grid)
        return theta, self._unwrapped(x, psi - theta, self.gamma_grid)

    def angles(self, x) -> tuple[np.ndarray, np.ndarray]:
        """Continuous theta(x) and gamma(x) over one cycle (x in [0, 2 pi]). At a touch the elbow
        angle is the square root of a rounding error (~1e-8 rad), so within TOUCH_LIMIT of one
        the angles are interpolated between the two sides (error O(TOUCH_LIMIT^2))."""
        x = np.asarray(x, float)
        theta, gamma = self._continuous(x)
        for touch, offset, near in self._near_touches(x):
            sides = self._continuous(np.mod(touch.parameter + np.array([-TOUCH_LIMIT, TOUCH_LIMIT]), TWO_PI))
            weight = (offset[near] + TOUCH_LIMIT) / (2 * TOUCH_LIMIT)
            grids = (self.theta_grid, self.gamma_grid)
            for values, (before, after), table in zip((theta, gamma), sides, grids, strict=True):
                after = before + np.angle(np.exp(1j * (after - before)))
                values[near] = self._unwrapped(x[near], before + weight * (after - before), table)
        return theta, gamma

    def _near_touches(self, x):
        """(touch, signed offset of x from it, mask of x within TOUCH_LIMIT) for each touch some x is near."""
        for touch in self.touches:
            offset = np.mod(x - touch.parameter + np.pi, TWO_PI) - np.pi
            near = np.abs(offset) < TOUCH_LIMIT
            if near.any():
                yield touch, offset, near

    def carrier_turn_at(self, x) -> np.ndarray:
        return self.direction * (self.angles(x)[0] - self.theta_grid[0])

    def net_turns(self) -> tuple[float, float]:
        """(carrier, planet against carrier) turns per cycle along the path, in turns."""
        return (self.direction * (self.theta_grid[-1] - self.theta_grid[0]) / TWO_PI,
                -self.direction * (self.gamma_grid[-1] - self.gamma_grid[0]) / TWO_PI)

    def path_rates(self, x) -> tuple[np.ndarray, np.ndarray]:
        """(d^k c / dx^k, d^k chi / dx^k) for k = 1..3, each (3, ...); on the spline segments of a touch from
        ``touch_rates`` (the closed form cancels there)."""
        return self._rates(np.mod(np.asarray(x, float), TWO_PI))

    def total_ratio(self) -> np.ndarray:
        """i0 = 1 / chi'(c), sun to planet in the carrier frame, on the reference grid."""
        (c1, _, _), (h1, _, _) = self.path_rates(self.grid)
        return c1 / h1

    @cached_property
    def touch_segments(self) -> tuple[TouchSegment, ...]:
        return touch_segments(self.trajectory, (self.carrier_length, self.arm_length), self.touches,
                              self.start_branch)

    def _rates(self, x):
        theta, psi = self.raw_angles(x)      # exactly at a touch the closed form divides 0 by 0
        path = np.concatenate([np.moveaxis(self.trajectory.evaluate(x, k), -1, 0) for k in (1, 2, 3)])
        with np.errstate(divide="ignore", invalid="ignore"):
            rates = _rates(np.array([theta, psi]), self.lengths[:, None], path)[0]
        flat = rates.reshape(6, -1)
        points = x.ravel()
        for segment in self.touch_segments:
            inside = (points >= segment.start) & (points < segment.start + segment.width)
            if inside.any():
                flat[:, inside] = segment.evaluate(points[inside])
        rates = flat.reshape(rates.shape)
        theta_k, psi_k = rates[0::2], rates[1::2]
        return self.direction * theta_k, -self.direction * (psi_k - theta_k)

    def parameter_at(self, c) -> np.ndarray:
        """x where the carrier has turned c (rad, in [0, 2 pi]), by Newton from the reference table."""
        c = np.asarray(c, float)
        table = self.direction * (self.theta_grid - self.theta_grid[0])
        x = np.interp(c, table, np.r_[self.grid, TWO_PI])
        for _ in range(40):
            with np.errstate(divide="ignore", invalid="ignore"):
                step = (self.carrier_turn_at(x) - c) / self.path_rates(x)[0][0]
            step = np.where(np.isfinite(step), step, 0.0)     # at a touch the rate is 0/0; x is exact there
            x = np.clip(x - step, 0.0, TWO_PI)
            if np.max(np.abs(step), initial=0.0) < 1e-13:
                break
        return x

    @property
    def knots(self) -> np.ndarray:
        """Breaks of the relative motion: carrier turns at the spline knots, and at each touch with
        panels graded geometrically away from it. Near a touch the rates divide by the distance
        to it, so the jump of P''' at a knot close by shows up in chi''' magnified by 1/distance^2."""
        touches = self.carrier_turn_at(np.array([t.parameter for t in self.touches]))
        grading = np.r_[0.0, np.outer([-1, 1], TOUCH_GRADING).ravel()]
        return np.unique(np.mod(np.r_[self.carrier_turn_at(self.trajectory.knots),
                                      (touches[:, None] + grading).ravel()], TWO_PI))


def touched_circle(extreme: RadialExtreme, carrier_length: float, arm_length: float) -> tuple[str, float] | None:
    """("outer" or "inner", gap in mm) when this extreme of |P| touches a reach circle, else None."""
    if extreme.kind == "farthest":
        bound, circle = carrier_length + arm_length, "outer"
    else:
        bound, circle = abs(carrier_length - arm_length), "inner"
    tolerance = TOUCH_TOLERANCE * (carrier_length + arm_length)
    return (circle, bound - extreme.radius) if abs(bound - extreme.radius) <= tolerance else None


def find_touches(trajectory: ClosedTrajectory, carrier_length: float, arm_length: float) -> tuple[Touch, ...]:
    touches = []
    for extreme in trajectory.radial_extremes():
        touched = touched_circle(extreme, carrier_length, arm_length)
        if touched:
            # a touch at the very start is put at the end of the cycle: the start branch holds from x = 0
            parameter = extreme.parameter if extreme.parameter > 1e-9 else TWO_PI
            touches.append(Touch(parameter, *touched))
    return tuple(sorted(touches, key=lambda touch: touch.parameter))


def solve_arm(trajectory: ClosedTrajectory, carrier_length: float, arm_length: float, direction: int,
              start_branch: int) -> ArmMotion:
    """The arm's motion on the given start branch, switching branch at every touch."""
    touches = find_touches(trajectory, carrier_length, arm_length)
    grid = np.linspace(0, TWO_PI, trajectory.count * GRID_PER_SEGMENT, endpoint=False)
    motion = ArmMotion(trajectory, carrier_length, arm_length, direction, start_branch, touches,
                       grid, np.zeros(0), np.zeros(0))
    theta, psi = motion.raw_angles(np.r_[grid, 0.0])
    theta = np.unwrap(theta)
    gamma = np.unwrap(psi - theta)
    motion = ArmMotion(trajectory, carrier_length, arm_length, direction, start_branch, touches, grid, theta, gamma)
    start = motion.angles(np.zeros(1))          # the references of c and chi, safe at a touch
    theta, gamma = (np.r_[s[0], v[1:-1], v[-1] + s[0] - v[0]] for s, v in zip(start, (theta, gamma), strict=True))
    return ArmMotion(trajectory, carrier_length, arm_length, direction, start_branch, touches, grid, theta, gamma)

"""A closed path of the arm tip: a uniform periodic cubic B-spline (the reverse-gear-design paper's 19-point curve).

The path parameter x runs over [0, 2 pi) once around the curve (reports give u = x / 2 pi,
so point k of the input sits at u = k / N). ``kind = "control_points"`` takes the points as
the control polygon (the curve passes near them); ``kind = "samples"`` takes them as points
on the curve and solves the cyclic system (d_{k-1} + 4 d_k + d_{k+1}) / 6 = q_k for the
control polygon, so the curve passes through every sample. Coordinates are relative to the
carrier pivot.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry import periodic_bspline
from transplanter.geometry.periodic_bspline import SEGMENT, TWO_PI


def interpolating_polygon(samples: np.ndarray) -> np.ndarray:
    """Control polygon of the periodic cubic B-spline through the samples at its knots."""
    n = len(samples)
    matrix = 4 * np.eye(n) + np.roll(np.eye(n), 1, axis=1) + np.roll(np.eye(n), -1, axis=1)
    return np.linalg.solve(matrix / 6, samples)


@dataclass(frozen=True)
class RadialExtreme:
    parameter: float        # x in [0, 2 pi)
    radius: float           # distance from the pivot, mm
    kind: str               # "farthest" (local maximum) or "nearest" (local minimum)


@dataclass(frozen=True)
class ClosedTrajectory:
    control: np.ndarray     # (N, 2) control polygon about the pivot, mm

    @property
    def count(self) -> int:
        return len(self.control)

    @property
    def knots(self) -> np.ndarray:
        return periodic_bspline.knots(self.count)

    def evaluate(self, x, order: int = 0) -> np.ndarray:
        """P or d^order P / dx^order at x (any shape) -> (..., 2)."""
        x = np.mod(np.asarray(x, float), TWO_PI)
        return np.stack([periodic_bspline.evaluate(x, self.control[:, j], order) for j in (0, 1)], axis=-1)

    def segment_polynomials(self) -> np.ndarray:
        """(N, 4, 2): P on segment k as sum_j c_j t^j with t = x N / 2 pi - k in [0, 1)."""
        index = (np.arange(self.count)[:, None] + np.arange(-1, 3)) % self.count
        return np.einsum("mj,kmd->kjd", SEGMENT, self.control[index])

    def radial_extremes(self) -> list[RadialExtreme]:
        """Every local maximum and minimum of |P| (roots of d|P|^2/dt per segment, exactly)."""
        extremes = []
        for k, c in enumerate(self.segment_polynomials()):
            square = np.convolve(c[:, 0], c[:, 0]) + np.convolve(c[:, 1], c[:, 1])
            slope = np.polynomial.polynomial.polyder(square)
            bend = np.polynomial.polynomial.polyder(slope)
            for root in np.polynomial.polynomial.polyroots(slope):
                if abs(root.imag) > 1e-9 or not -1e-9 <= root.real <= 1 + 1e-9:   # a root at a joint may fall either side
                    continue
                t = root.real
                curvature = np.polynomial.polynomial.polyval(t, bend)
                if curvature == 0:
                    continue
                radius = float(np.sqrt(np.polynomial.polynomial.polyval(t, square)))
                extremes.append(RadialExtreme(float(np.mod(TWO_PI * (k + t) / self.count, TWO_PI)), radius,
                                              "farthest" if curvature < 0 else "nearest"))
        extremes.sort(key=lambda e: e.parameter)
        # a root at a joint is found by both segments that meet there: keep one
        gaps = np.diff([e.parameter for e in extremes] + [extremes[0].parameter + TWO_PI]) if extremes else []
        return [e for e, gap in zip(extremes, gaps) if gap > 1e-8]

    def turning_speed_floor(self, samples_per_segment: int = 64) -> tuple[float, float]:
        """(smallest |P'|, where): zero means the curve stops (a cusp of the control polygon)."""
        x = np.linspace(0, TWO_PI, self.count * samples_per_segment, endpoint=False)
        speed = np.linalg.norm(self.evaluate(x, 1), axis=-1)
        k = int(np.argmin(speed))
        return float(speed[k]), float(x[k])

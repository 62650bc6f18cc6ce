"""A closed path of the arm tip: a uniform periodic cubic B-spline (the reverse-gear-design paper's 19-point curve).

The path parameter x runs over [0, 2 pi) once around the curve (reports give u = x / 2 pi,
so point k of the input sits at u = k / N). ``kind = "control_points"`` takes the points as
the control polygon (the curve passes near them); ``kind = "samples"`` takes them as points
on the curve, sample k at x = 2 pi k / N, and fits a control polygon of fewer points by least
squares (``fitted_polygon``: the count that minimises generalised cross-validation, so noise is
not followed into the curvature the gears are cut from). ``interpolating_polygon`` gives the
curve through every sample. Coordinates are relative to the carrier pivot.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry import periodic_bspline
from transplanter.geometry.periodic_bspline import SEGMENT
from transplanter.geometry.planar import TWO_PI


def interpolating_polygon(samples: np.ndarray) -> np.ndarray:
    """Control polygon of the periodic cubic B-spline through the samples at its knots."""
    n = len(samples)
    matrix = 4 * np.eye(n) + np.roll(np.eye(n), 1, axis=1) + np.roll(np.eye(n), -1, axis=1)
    return np.linalg.solve(matrix / 6, samples)


def _least_squares_polygon(samples: np.ndarray, count: int) -> tuple[np.ndarray, float]:
    """Control polygon of ``count`` points whose curve passes nearest the samples, and the sum of
    squared misses (mm^2). The normal matrix of the periodic cubic basis is banded and small."""
    basis = periodic_bspline.basis_matrix(periodic_bspline.knots(len(samples)), count)
    control = np.linalg.solve(basis.T @ basis, basis.T @ samples)
    return control, float(np.sum((basis @ control - samples) ** 2))


#: Control-point counts a fit tries: from the first, growing by the factor, up to the last (or two
#: fewer than the samples). 256 points follow a smooth loop to about 1e-9 of its size, and the arm's
#: inverse kinematics costs grow with the count.
FIT_COUNTS = (8, 1.25, 256)


def fitted_polygon(samples: np.ndarray) -> np.ndarray:
    """Control polygon fitted to closed-path samples (N, 2): of the counts 8, 10, 12, ... up to
    min(256, N - 2), the one that minimises generalised cross-validation, (RSS / N) / (1 - count / N)^2
    (Craven and Wahba's score: misses that only shrink by following noise do not pay for the
    extra points). Fewer than 16 samples are interpolated."""
    n = len(samples)
    first, factor, last = FIT_COUNTS
    if n < 2 * first:
        return interpolating_polygon(samples)
    last = min(last, n - 2)
    counts, count = [last], float(first)
    while count < last:
        counts.append(int(round(count)))
        count *= factor
    scored = []
    for count in sorted(set(counts)):
        control, squares = _least_squares_polygon(samples, count)
        scored.append((squares / n / (1 - count / n) ** 2, control))
    return min(scored, key=lambda item: item[0])[1]


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
                # a root at a joint may fall either side
                if abs(root.imag) > 1e-9 or not -1e-9 <= root.real <= 1 + 1e-9:
                    continue
                t = root.real
                curvature = np.polynomial.polynomial.polyval(t, bend)
                if curvature == 0:
                    continue
                radius = float(np.sqrt(np.polynomial.polynomial.polyval(t, square)))
                extremes.append(RadialExtreme(float(np.mod(TWO_PI * (k + t) / self.count, TWO_PI)), radius,
                                              "farthest" if curvature < 0 else "nearest"))
        if not extremes:
            return []
        extremes.sort(key=lambda e: e.parameter)
        # a root at a joint is found by both segments that meet there: keep one
        gaps = np.diff([e.parameter for e in extremes] + [extremes[0].parameter + TWO_PI])
        return [e for e, gap in zip(extremes, gaps, strict=True) if gap > 1e-8]

    def sample_misses(self, samples: np.ndarray) -> np.ndarray:
        """Distance of each sample (N, 2), sample k taken at x = 2 pi k / N, from the curve there (mm)."""
        return np.linalg.norm(self.evaluate(periodic_bspline.knots(len(samples))) - samples, axis=1)

    def radially_remapped(self, farthest: float, nearest: float) -> ClosedTrajectory:
        """The curve with its control points moved radially, r -> a + b r about the pivot, so that its
        farthest and nearest distances from the pivot are exactly ``farthest`` and ``nearest`` (Newton
        on a, b; the curve's extremes, not the control points', are matched)."""
        radius = np.linalg.norm(self.control, axis=1)
        if not radius.all():
            raise ValueError("a control point on the pivot has no radial direction")
        direction = self.control / radius[:, None]

        def miss(ab):
            remapped = ClosedTrajectory(direction * (ab[0] + ab[1] * radius)[:, None])
            radii = [e.radius for e in remapped.radial_extremes()]
            return np.array([max(radii) - farthest, min(radii) - nearest])

        ab, size = np.array([0.0, 1.0]), farthest
        for _ in range(30):
            residual = miss(ab)
            if np.abs(residual).max() <= 1e-13 * size:
                break
            steps = np.diag([1e-7 * size, 1e-7])
            jacobian = np.column_stack([(miss(ab + step) - residual) / step.max() for step in steps])
            ab = ab - np.linalg.solve(jacobian, residual)
        return ClosedTrajectory(direction * (ab[0] + ab[1] * radius)[:, None])

    def turning_speed_floor(self, samples_per_segment: int = 64) -> tuple[float, float]:
        """(smallest |P'|, where): zero means the curve stops (a cusp of the control polygon)."""
        x = np.linspace(0, TWO_PI, self.count * samples_per_segment, endpoint=False)
        speed = np.linalg.norm(self.evaluate(x, 1), axis=-1)
        k = int(np.argmin(speed))
        return float(speed[k]), float(x[k])

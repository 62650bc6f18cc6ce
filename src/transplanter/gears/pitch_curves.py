"""Driver pitch curves r(phi) of the gear families, with exact derivatives.

Analytic families are built as casadi expressions of phi; their slope dr/dphi and bend
d2r/dphi2 come from casadi's automatic differentiation. A sampled curve is a periodic
cubic spline with its own exact derivatives. All curves are 2 pi periodic in phi
(radians, in the gear's own frame) and list the angles where a piecewise definition
joins (``joints``), so integrals and continuity checks can respect them.

Families (the onion-transplanter paper eq 1-3; higher-order ellipse: r = a (1 - e^2) / (1 - e cos(n phi))):
- ``ellipse``, ``higher_order_ellipse``: semi-major axis a, eccentricity e, order n;
- ``denatured_ellipse``: the ellipse with its two half-turns stretched by m11 and m12;
- ``limacon``: base + amplitude cos(n phi);
- ``denatured_limacon``: the onion-transplanter paper eq (3), halves stretched by m11 and m12 with
  pi/m11 + pi/m12 = 2 pi (eq 2);
- ``spline``: a periodic cubic spline through sampled (phi, r).
"""
from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TypeVar

import casadi as ca
import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from transplanter.geometry.planar import TWO_PI

#: The smallest pitch radius, as a fraction of the curve's largest: nearer the centre the transmission ratio leaves
#: the thousandfold range every family keeps (gears.problem.RATIO_RANGE), and closure loses its digits.
SMALLEST_RADIUS = 1e-3


def too_small_radius(phi: np.ndarray, radius: np.ndarray, largest: float) -> str | None:
    """Where the pitch ``radius`` sampled at ``phi`` falls below ``SMALLEST_RADIUS`` of ``largest`` (mm), or None."""
    if radius.min() >= SMALLEST_RADIUS * largest:
        return None
    k = int(np.argmin(radius))
    return (f"the pitch radius reaches {radius[k]:.6g} mm at phi = {np.degrees(phi[k]):.2f} deg: expected at least "
            f"{SMALLEST_RADIUS:g} of the largest ({largest:.6g} mm) all round")


FloatOrArray = TypeVar("FloatOrArray", float, np.ndarray)
#: r (or a ratio) and its first two derivatives at an array of angles.
Evaluator = Callable[[np.ndarray], Sequence[np.ndarray]]


def denatured_partner(m11: FloatOrArray) -> FloatOrArray:
    """m12 from the onion-transplanter paper eq (2): pi/m11 + pi/m12 = 2 pi."""
    return 1.0 / (2.0 - 1.0 / m11)


@dataclass(frozen=True)
class PitchCurve:
    """r(phi) with slope and bend; ``lobes`` is the order n1 (how many times r repeats per turn).

    ``breaks`` are angles where the definition changes piece (joints of a piecewise curve,
    spline knots): integrals are split there.
    """

    family: str
    parameters: dict
    lobes: int
    evaluator: Evaluator = field(repr=False, compare=False)
    joints: tuple[float, ...] = ()
    breaks: tuple[float, ...] = ()
    scale: float = 1.0

    def evaluate(self, phi) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(r, dr/dphi, d2r/dphi2) at the angles ``phi`` (any shape), in mm."""
        phi = np.asarray(phi, float)
        r, slope, bend = (self.scale * np.asarray(v, float).reshape(phi.shape)
                          for v in self.evaluator(np.mod(phi.ravel(), TWO_PI)))
        return r, slope, bend

    def scaled(self, factor: float) -> PitchCurve:
        return dataclasses.replace(self, scale=self.scale * factor)


@functools.lru_cache(maxsize=64)
def _mapped(function: ca.Function, count: int) -> ca.Function:
    return function.map(count)


@dataclass(frozen=True)
class _Derivatives:
    """A casadi Function of one angle giving a value and its first two derivatives, evaluated over an array of
    angles (a class, not a closure, so that curves and results pickle: casadi Functions do)."""

    function: ca.Function

    def __call__(self, phi: np.ndarray) -> list[np.ndarray]:
        return [np.asarray(v).ravel() for v in _mapped(self.function, phi.size)(phi[None, :])]


def _derivatives(name: str, expression: ca.SX, phi: ca.SX) -> _Derivatives:
    slope = ca.jacobian(expression, phi)
    return _Derivatives(ca.Function(name, [phi], [expression, slope, ca.jacobian(slope, phi)]))


@dataclass(frozen=True)
class Shifted:
    """An evaluator read ``angle`` (rad) further round: ``evaluator(phi + angle)``."""

    evaluator: Evaluator
    angle: float

    def __call__(self, phi: np.ndarray):
        return self.evaluator(np.mod(phi + self.angle, TWO_PI))


def _from_expression(family, parameters, lobes, expression_of, joints=()) -> PitchCurve:
    phi = ca.SX.sym("phi")
    evaluate = _derivatives(f"{family}_pitch", expression_of(phi), phi)
    return PitchCurve(family, parameters, lobes, evaluate, tuple(joints), tuple(joints))


def ellipse(semi_major_axis: float, eccentricity: float, order: int = 1) -> PitchCurve:
    p = semi_major_axis * (1 - eccentricity**2)
    family = "ellipse" if order == 1 else "higher_order_ellipse"
    return _from_expression(family, {"semi_major_axis": semi_major_axis, "eccentricity": eccentricity, "order": order},
                            order, lambda phi: p / (1 - eccentricity * ca.cos(order * phi)))


def limacon(base: float, amplitude: float, order: int = 1) -> PitchCurve:
    return _from_expression("limacon", {"base": base, "amplitude": amplitude, "order": order},
                            order, lambda phi: base + amplitude * ca.cos(order * phi))


def _denatured(family, parameters, shape, m11, m12):
    """shape(t) on t in [0, pi] for the first half (t = m11 phi) and mirrored for the second
    (t = m12 (2 pi - phi)); the halves join at phi = pi / m11."""
    joint = np.pi / m11
    return _from_expression(family, {**parameters, "m11": m11, "m12": m12}, 1,
                            lambda phi: ca.if_else(phi <= joint, shape(m11 * phi), shape(m12 * (TWO_PI - phi))),
                            joints=(joint,))


def denatured_ellipse(semi_major_axis: float, eccentricity: float, m11: float, m12: float) -> PitchCurve:
    p = semi_major_axis * (1 - eccentricity**2)
    return _denatured("denatured_ellipse", {"semi_major_axis": semi_major_axis, "eccentricity": eccentricity},
                      lambda t: p / (1 - eccentricity * ca.cos(t)), m11, m12)


def denatured_limacon(base: float, amplitude: float, m11: float, m12: float) -> PitchCurve:
    """The onion-transplanter paper eq (3) with b = amplitude and l = base."""
    return _denatured("denatured_limacon", {"base": base, "amplitude": amplitude},
                      lambda t: base + amplitude * ca.cos(t), m11, m12)


class PeriodicSpline:
    """Periodic cubic spline through (phi_k, r_k), phi in [0, 2 pi); C2 everywhere."""

    def __init__(self, phi: np.ndarray, radius: np.ndarray):
        order = np.argsort(phi)
        self.knots = np.asarray(phi, float)[order]
        self.values = np.asarray(radius, float)[order]
        h = np.diff(np.r_[self.knots, self.knots[0] + TWO_PI])
        n = len(h)
        # Second derivatives M_k: h_{k-1} M_{k-1} + 2 (h_{k-1} + h_k) M_k + h_k M_{k+1} = 6 (slope_k - slope_{k-1})
        slopes = (np.roll(self.values, -1) - self.values) / h
        # cyclic tridiagonal, as a sparse matrix (entries that fall on one place, as for n < 3, are summed): the
        # solve is linear in n where a dense one took n^2 memory (20,000 samples: 3 GB)
        rows = np.repeat(np.arange(n), 3)
        columns = (rows + np.tile([-1, 0, 1], n)) % n
        before = np.roll(h, 1)
        entries = np.column_stack([before, 2 * (before + h), h]).ravel()
        matrix = scipy.sparse.csc_matrix((entries, (rows, columns)), shape=(n, n))
        self.second = np.atleast_1d(scipy.sparse.linalg.spsolve(matrix, 6 * (slopes - np.roll(slopes, 1))))
        self.widths = h

    def evaluate(self, phi: np.ndarray):
        k = np.searchsorted(self.knots, phi, side="right") - 1
        k = np.where(k < 0, len(self.knots) - 1, k)
        t = phi - self.knots[k]
        t = np.where(t < 0, t + TWO_PI, t)
        h, m0, m1 = self.widths[k], self.second[k], self.second[(k + 1) % len(self.knots)]
        y0, y1 = self.values[k], self.values[(k + 1) % len(self.knots)]
        u = h - t
        r = (m0 * u**3 + m1 * t**3) / (6 * h) + (y0 / h - m0 * h / 6) * u + (y1 / h - m1 * h / 6) * t
        slope = (-m0 * u**2 + m1 * t**2) / (2 * h) - (y0 / h - m0 * h / 6) + (y1 / h - m1 * h / 6)
        bend = (m0 * u + m1 * t) / h
        return r, slope, bend


def spline(phi: np.ndarray, radius: np.ndarray) -> PitchCurve:
    """Pitch curve through sampled radii (one turn)."""
    curve = PeriodicSpline(np.mod(phi, TWO_PI), radius)
    return PitchCurve("spline", {"samples": len(curve.knots)}, 1, curve.evaluate, (), tuple(curve.knots))


def ratio_samples(phi: np.ndarray, ratio: np.ndarray) -> Evaluator:
    """i12 and its two derivatives from samples (periodic cubic spline)."""
    return PeriodicSpline(np.mod(phi, TWO_PI), ratio).evaluate


def ratio_formula(expression: ca.SX, phi: ca.SX) -> Evaluator:
    """i12 and its two derivatives from a casadi expression of phi (automatic differentiation)."""
    return _derivatives("ratio", expression, phi)


@dataclass(frozen=True)
class _FromRatio:
    """r1 = a / (1 + k i12) and its two derivatives, from i12 and its own (``from_ratio``)."""

    ratio: Evaluator
    factor: float
    center_distance: float

    def __call__(self, phi: np.ndarray) -> tuple:
        a = self.center_distance
        i, di, ddi = (self.factor * v for v in self.ratio(phi))
        one = 1 + i
        return a / one, -a * di / one**2, a * (2 * di**2 / one**3 - ddi / one**2)


def from_ratio(ratio: Evaluator, factor: float, center_distance: float,
               breaks=()) -> PitchCurve:
    """Driver pitch curve r1 = a / (1 + k i12) for a ratio i12 = omega1 / omega2 (the onion-transplanter paper eq 13),
    scaled by a constant k (Wang et al. 2025 eq 12)."""
    return PitchCurve("ratio", {"center_distance": center_distance, "factor": factor}, 1,
                      _FromRatio(ratio, factor, center_distance), (), tuple(breaks))

"""Closed pitch curves made of segments joined in position, with corners (the cusp-pitch-curve
paper, section 2, Figure 2).

Each segment is a polar curve r(phi) about the gear centre on its own angle range; the ranges
follow one another round the turn. A segment is

- ``line``: the straight line at ``distance`` from the centre whose normal points at
  ``normal`` (r = d / cos(phi - normal)); without them, the chord between the ends of its
  neighbouring segments;
- ``arc``: the circle of ``radius`` about ``center`` (its far intersection with the ray);
- any analytic family of ``pitch_curves`` (ellipse, limacon, ...), turned by ``rotation``.

Radii and slopes come from casadi's automatic differentiation of each segment's expression, as
for every other family. At each joint r is continuous (checked) and r' may jump: the tangent
then turns by the jump of mu = atan2(r, r') (derivations/cusp.py), a cusp. Straight segments
are flagged so their curvature radius is exactly infinite.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from transplanter._generated.cusp import corner_angles, polar_curvature_center
from transplanter.errors import ProblemError
from transplanter.gears.pitch_curves import PitchCurve, Shifted, _from_expression, too_small_radius
from transplanter.generated import numpy_twin
from transplanter.geometry.planar import TWO_PI

_corner_angles = numpy_twin(corner_angles)
_curvature_center = numpy_twin(polar_curvature_center)
#: One-sided values at a joint are taken this far (rad) inside each segment.
SIDE = 1e-9
#: Joints whose radii differ by more than this fraction of the largest radius do not join.
JOIN_TOLERANCE = 1e-7
#: A tangent turn below this (rad) is a smooth joint, not a cusp.
CUSP_TOLERANCE = 1e-6


@dataclass(frozen=True)
class Segment:
    """One piece of a composite curve on [start, end] (rad, start < end, unwrapped)."""

    kind: str
    start: float
    end: float
    curve: PitchCurve
    straight: bool = False


def line(distance: float, normal: float) -> PitchCurve:
    """The straight line {x . e(normal) = distance} as r(phi) = d / cos(phi - normal)."""
    return _from_expression("line", {"distance": distance, "normal": normal}, 1,
                            lambda phi: distance / ca.cos(phi - normal))


def chord(start_point: np.ndarray, end_point: np.ndarray) -> PitchCurve:
    """The line through two points (mm), as ``line``."""
    direction = end_point - start_point
    normal = np.arctan2(-direction[0], direction[1])
    distance = float(np.dot(start_point, [np.cos(normal), np.sin(normal)]))
    if distance < 0:
        normal, distance = normal + np.pi, -distance
    return line(distance, float(normal))


def arc(center: tuple[float, float], radius: float) -> PitchCurve:
    """The circle of ``radius`` about ``center``: r = c . u + sqrt(R^2 - (c x u)^2)."""
    cx, cy = center
    return _from_expression("arc", {"center": [cx, cy], "radius": radius}, 1,
                            lambda phi: cx * ca.cos(phi) + cy * ca.sin(phi)
                            + ca.sqrt(radius**2 - (cx * ca.sin(phi) - cy * ca.cos(phi)) ** 2))


def rotated(curve: PitchCurve, rotation: float) -> PitchCurve:
    """A family's curve turned counterclockwise by ``rotation`` (rad)."""
    return PitchCurve(curve.family, {**curve.parameters, "rotation": rotation}, 1, Shifted(curve.evaluator, -rotation))


@dataclass(frozen=True)
class CompositeCurve(PitchCurve):
    """A pitch curve of ``segments`` (one turn); joints at the segment ends."""

    segments: tuple[Segment, ...] = field(default=(), repr=False, compare=False)

    def segment_index(self, phi) -> np.ndarray:
        """Which segment covers each angle (rad, any shape)."""
        first = self.segments[0].start
        local = np.mod(np.asarray(phi, float) - first, TWO_PI) + first
        ends = np.array([s.end for s in self.segments])
        return np.minimum(np.searchsorted(ends, local, side="right"), len(self.segments) - 1)

    def straight(self, phi) -> np.ndarray:
        """True where the angle lies on a straight segment."""
        flags = np.array([s.straight for s in self.segments])
        return flags[self.segment_index(phi)]

    def one_sided(self, joint: int) -> tuple[tuple, tuple]:
        """(r, r', r'') just before and just after the start of segment ``joint`` (mm, scaled)."""
        before, after = self.segments[joint - 1], self.segments[joint]
        angle = after.start
        left = before.curve.evaluate(np.array([angle - SIDE]))
        right = after.curve.evaluate(np.array([angle + SIDE]))
        return (tuple(self.scale * v[0] for v in left), tuple(self.scale * v[0] for v in right))


def composite(segments: list[Segment], source: str = "<gear>", where: str = "driver.segments") -> CompositeCurve:
    """The closed curve of ``segments`` in order round the turn; refuses gaps and radii that do not join.

    Raises
    ------
    ProblemError
        Naming the segment whose angle range or end radius does not meet its neighbour's.
    """
    for k, (a, b) in enumerate(zip(segments, segments[1:] + segments[:1], strict=True)):
        expected = b.start + (TWO_PI if k == len(segments) - 1 else 0.0)
        if abs(a.end - expected) > 1e-12 or a.end <= a.start:
            raise ProblemError(f"{source}: {where}[{k}].phi_deg = [{np.degrees(a.start):g}, {np.degrees(a.end):g}]: "
                               f"expected a range that ends where segment {(k + 1) % len(segments)} starts "
                               f"({np.degrees(expected):g} deg), the last one a full turn after the first starts")
    size = max(float(np.abs(s.curve.evaluate(np.linspace(s.start, s.end, 64))[0]).max()) for s in segments)
    for k, segment in enumerate(segments):
        phi = np.linspace(segment.start, segment.end, 2001)
        with np.errstate(all="ignore"):
            radius = np.nan_to_num(segment.curve.evaluate(phi)[0], nan=0.0, posinf=-np.inf)
        defect = too_small_radius(phi, radius, size)
        if defect:
            raise ProblemError(f"{source}: {where}[{k}]: {defect}" + ("; a line (or chord) must pass the gear centre "
                                                                     "at a distance, within 90 deg of its normal"
                                                                     if segment.kind == "line" else ""))
    for k, (a, b) in enumerate(zip(segments, segments[1:] + segments[:1], strict=True)):
        r_end, r_start = a.curve.evaluate(np.array([a.end]))[0][0], b.curve.evaluate(np.array([b.start]))[0][0]
        if not (np.isfinite(r_end) and np.isfinite(r_start)) or abs(r_end - r_start) > JOIN_TOLERANCE * size:
            raise ProblemError(f"{source}: {where}[{(k + 1) % len(segments)}]: starts at r = {r_start:.9g} mm where "
                               f"segment {k} ends at r = {r_end:.9g} mm (phi = {np.degrees(b.start):g} deg): "
                               f"expected the segments to join (within {JOIN_TOLERANCE * size:.2g} mm)")
    ordered = tuple(segments)
    joints = tuple(float(np.mod(s.start, TWO_PI)) for s in ordered)
    parameters = {"segments": [s.kind for s in ordered]}
    return CompositeCurve("composite", parameters, 1, _Piecewise(ordered), joints, joints, segments=ordered)


@dataclass(frozen=True)
class _Piecewise:
    """r, r', r'' of a composite curve: each angle from the segment whose range holds it."""

    segments: tuple

    def __call__(self, phi: np.ndarray) -> list[np.ndarray]:
        first, ends = self.segments[0].start, np.array([s.end for s in self.segments])
        local = np.mod(phi - first, TWO_PI) + first
        index = np.minimum(np.searchsorted(ends, local, side="right"), len(self.segments) - 1)
        out = [np.empty_like(local) for _ in range(3)]
        for k, segment in enumerate(self.segments):
            chosen = index == k
            if chosen.any():
                for target, value in zip(out, segment.curve.evaluate(local[chosen]), strict=True):
                    target[chosen] = value
        return out


def cusps(curve: CompositeCurve, center_distance: float | None = None) -> list[dict]:
    """Every joint where the tangent turns: angle (deg), the driver's turn (deg, + convex) and, given the
    center distance, the driven curve's turn at the same contact (deg, its own counterclockwise sense)."""
    out = []
    for k in range(len(curve.segments)):
        (r_left, s_left, _), (r_right, s_right, _) = curve.one_sided(k)
        a = center_distance if center_distance is not None else 2 * max(r_left, r_right)
        (mu1_left,), (mu2_left,) = _corner_angles([a], [r_left], [s_left])
        (mu1_right,), (mu2_right,) = _corner_angles([a], [r_right], [s_right])
        turn = float(mu1_right - mu1_left)
        if abs(turn) > CUSP_TOLERANCE:
            entry = {"phi_deg": float(np.degrees(np.mod(curve.segments[k].start, TWO_PI))),
                     "turn_deg": float(np.degrees(turn))}
            if center_distance is not None:     # the driven curve runs the other way: left side comes after
                entry["driven_turn_deg"] = float(np.degrees(mu2_left - mu2_right))
            out.append(entry)
    return out


def curvature(curve: PitchCurve, phi: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Curvature radius (mm, inf on straight segments), convexity (r^2 + 2 r'^2 - r r''; 0 on straight
    segments) and curvature centre (N, 2) (NaN on straight segments) at the angles ``phi`` (the cusp-pitch-curve
    paper, eq 1)."""
    r, slope, bend = curve.evaluate(phi)
    straight = curve.straight(phi) if isinstance(curve, CompositeCurve) else np.zeros(phi.shape, bool)
    with np.errstate(divide="ignore", invalid="ignore"):
        center, (cross,) = _curvature_center([r], [slope], [bend], [phi])
        radius = np.hypot(r, slope) ** 3 / cross
    cross = np.where(straight, 0.0, cross)
    radius = np.where(straight, np.inf, radius)
    center = np.where(straight[None], np.nan, center)
    return radius, cross, center.T


def with_exact_curvature(design):
    """A ``GearPairDesign`` whose driver curvature is exact on straight segments (infinite radius, zero convexity)."""
    radius, cross, _ = curvature(design.driver, design.phi1)
    return dataclasses.replace(design, curvature_radius=(radius, design.curvature_radius[1]),
                               convexity=(cross, design.convexity[1]))


def segment_frame(curve: CompositeCurve, segment: int, phi: np.ndarray):
    """Points, unit tangents and outward normals (N, 2) of one segment's own curve at the angles ``phi``
    (rad; also past its ends, so each side of a corner has its own frame)."""
    r, slope, _ = (curve.scale * v for v in curve.segments[segment].curve.evaluate(phi))
    u = np.c_[np.cos(phi), np.sin(phi)]
    tangent = slope[:, None] * u + r[:, None] * np.c_[-u[:, 1], u[:, 0]]
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    return r[:, None] * u, tangent, np.c_[tangent[:, 1], -tangent[:, 0]]

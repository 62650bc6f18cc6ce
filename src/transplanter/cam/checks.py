"""Checks of a cam, each with where in the cycle it happens: the largest pressure angle on rises and
returns against the limit, undercut (a convex stretch of pitch curve sharper than the roller), the
roller cutting into the profile elsewhere (a concave stretch narrower than the roller), and jumps of
acceleration between segments.

Extremes found on the samples are polished by zooming in between the neighbouring samples, kept
within one segment (the acceleration, and so the curvature, may jump between two).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.spatial import cKDTree

from transplanter.cam.kinematics import CamGeometry, evaluate, segment_levels, segment_motion, segment_starts
from transplanter.cam.problem import CamProblem

#: The roller cuts into the profile where a profile point is nearer its centre than this share of its radius.
INTERFERENCE_SHARE = 1e-6
#: Extremes on the samples are polished by this many zooms of this many angles (each zoom 16 times finer).
POLISH_ROUNDS, POLISH_POINTS = 5, 33
#: An acceleration jump smaller than this share of the largest acceleration is continuity.
JUMP_SHARE = 1e-9


@dataclass(frozen=True)
class Extreme:
    """A value and the cam angle (rad) where it is reached."""

    value: float
    angle: float


@dataclass(frozen=True)
class Stretch:
    """Cam angles (rad) from ``start`` to ``end`` (through 0 when ``end`` < ``start``) where a check
    fails, and its worst value there (mm)."""

    start: float
    end: float
    worst: float


@dataclass(frozen=True)
class AccelerationJump:
    """At cam angle ``angle`` (rad), between segments ``before`` and ``after``: the follower's acceleration
    (mm/rad^2, or rad/rad^2 for a swing) jumps by ``size``."""

    angle: float
    before: int
    after: int
    size: float


@dataclass(frozen=True)
class CamChecks:
    """What the checks found on a ``CamGeometry``.

    Attributes
    ----------
    pressure : dict
        ``"rise"`` and ``"return"`` -> Extreme of |pressure angle| (rad), None without such segments.
    min_pitch_radius, min_profile_radius : Extreme or None
        Smallest curvature radius on convex stretches of the pitch curve and of the profile (mm; the
        profile's is the pitch curve's less the roller radius, negative where undercut).
    min_concave_profile_radius : Extreme or None
        Smallest |curvature radius| of the profile's concave stretches (mm).
    undercut, interference : tuple of Stretch
        Convex stretches with pitch radius below the roller radius (worst: that radius); stretches where
        the roller centred on the pitch curve overlaps the profile elsewhere (worst: the overlap, mm). For a
        flat-faced follower ``undercut`` holds the stretches its face cannot follow: a profile radius at or
        below zero (a cusp or a concave stretch; worst: the radius).
    acceleration_jumps : tuple of AccelerationJump
    pressure_limit : float
        rad.
    """

    pressure: dict
    min_pitch_radius: Extreme | None
    min_profile_radius: Extreme | None
    min_concave_profile_radius: Extreme | None
    undercut: tuple[Stretch, ...]
    interference: tuple[Stretch, ...]
    acceleration_jumps: tuple[AccelerationJump, ...]
    pressure_limit: float
    flat_faced: bool = False
    profile_radius_limit: float = 0.0

    @property
    def failures(self) -> list[str]:
        out = []
        for kind, extreme in self.pressure.items():
            if extreme is not None and extreme.value > self.pressure_limit:
                out.append(f"largest pressure angle on {kind} {np.degrees(extreme.value):.3f} deg at cam angle "
                           f"{np.degrees(extreme.angle):.2f} deg exceeds the limit "
                           f"{np.degrees(self.pressure_limit):g} deg")
        for stretch in self.undercut if self.flat_faced else ():
            out.append(f"the flat face cannot follow the profile from cam angle {np.degrees(stretch.start):.2f} to "
                       f"{np.degrees(stretch.end):.2f} deg: its curvature radius R_b + s + s'' falls to "
                       f"{stretch.worst:.4f} mm (concave or a cusp)")
        for stretch in self.undercut if not self.flat_faced else ():
            out.append(f"undercut from cam angle {np.degrees(stretch.start):.2f} to {np.degrees(stretch.end):.2f} deg: "
                       f"the pitch curve's convex radius falls to {stretch.worst:.4f} mm, below the roller radius")
        smallest = self.min_profile_radius
        if self.profile_radius_limit > 0 and smallest is not None and 0 < smallest.value < self.profile_radius_limit:
            out.append(f"the profile's smallest convex radius {smallest.value:.4f} mm at cam angle "
                       f"{np.degrees(smallest.angle):.2f} deg is below "
                       f"limits.profile_radius_mm = {self.profile_radius_limit:g}")
        for stretch in self.interference:
            out.append(f"the roller cuts {stretch.worst:.4f} mm into the profile from cam angle "
                       f"{np.degrees(stretch.start):.2f} to {np.degrees(stretch.end):.2f} deg")
        return out

    @property
    def passed(self) -> bool:
        return not self.failures


def runs(mask: np.ndarray) -> list[np.ndarray]:
    """Indices of each run of True in a cyclic boolean array (a run may wrap through index 0)."""
    if mask.all():
        return [np.arange(mask.size)]
    shift = int(np.argmin(mask))                      # start the cycle on a False
    rolled = np.roll(mask, -shift)
    edges = np.flatnonzero(np.diff(np.concatenate([[0], rolled.astype(int), [0]])))
    return [(np.arange(a, b) + shift) % mask.size for a, b in zip(edges[::2], edges[1::2], strict=True)]


def _polish(problem, base_radius, geometry, k, quantity, bounds_segment) -> Extreme:
    """The minimum of ``quantity(geometry_at_angles)`` near sample ``k``, within segment ``bounds_segment``:
    ``POLISH_ROUNDS`` zooms of ``POLISH_POINTS`` angles each, every zoom one vectorised evaluation."""
    starts = segment_starts(problem.segments)
    step = 2 * np.pi / geometry.angle.size
    low, high = starts[bounds_segment], starts[bounds_segment + 1]
    best = Extreme(float(quantity(geometry)[k]), float(geometry.angle[k]))
    for _ in range(POLISH_ROUNDS):
        angles = np.linspace(max(best.angle - step, low), min(best.angle + step, high), POLISH_POINTS)
        values = quantity(evaluate(problem, base_radius, angles, bounds_segment))
        j = int(np.argmin(values))
        if values[j] <= best.value:
            best = Extreme(float(values[j]), float(angles[j]))
        step = 2 * step / (POLISH_POINTS - 1)
    return best


def _smallest(problem, base_radius, geometry, quantity, mask) -> Extreme | None:
    if not mask.any():
        return None
    values = np.where(mask, quantity(geometry), np.inf)
    k = int(np.argmin(values))
    return _polish(problem, base_radius, geometry, k, quantity, int(geometry.segment[k]))


def _with_extreme(stretches: tuple[Stretch, ...], extreme: Extreme | None, limit: float,
                  step: float) -> tuple[Stretch, ...]:
    """``stretches`` found on the samples (``step`` apart), widened to the polished ``extreme`` when it falls below
    ``limit`` (e.g. the sharpest point of a segment is its end, where the next segment's sample sits), or with it
    as a stretch of its own when no stretch is within a sample of it."""
    if extreme is None or extreme.value >= limit:
        return stretches
    out, found = [], False
    for stretch in stretches:
        start, end = stretch.start - step, stretch.end + step
        near = start <= extreme.angle <= end if stretch.start <= stretch.end else not end < extreme.angle < start
        if near and not found:
            found = True
            worst = min(stretch.worst, extreme.value)
            if stretch.start <= stretch.end:
                stretch = Stretch(min(stretch.start, extreme.angle), max(stretch.end, extreme.angle), worst)
            else:                       # through 0: the extreme is within a sample of it, keep its ends
                stretch = Stretch(stretch.start, stretch.end, worst)
        out.append(stretch)
    return tuple(out) if found else (*out, Stretch(extreme.angle, extreme.angle, extreme.value))


def pressure_extremes(problem: CamProblem, geometry: CamGeometry) -> dict:
    """Largest |pressure angle| on the rises and on the returns (polished), or None."""
    kinds = np.array([s.kind for s in problem.segments])[geometry.segment]
    out = {}
    for kind in ("rise", "return"):
        least = _smallest(problem, geometry.base_radius, geometry, lambda g: -np.abs(g.pressure_angle), kinds == kind)
        out[kind] = None if least is None else Extreme(-least.value, least.angle)
    return out


def _stretches(geometry: CamGeometry, mask: np.ndarray, worst: np.ndarray, pick) -> tuple[Stretch, ...]:
    angle = geometry.angle
    return tuple(Stretch(float(angle[run[0]]), float(angle[run[-1]]), float(pick(worst[run]))) for run in runs(mask))


def interference(geometry: CamGeometry, roller_radius: float) -> tuple[Stretch, ...]:
    """Stretches where a profile point lies nearer a roller centre than the roller radius: the roller
    would cut into the cam there. Distances to the profile's vertices bound those to the profile from
    above, so an overlap found is real."""
    distance, _ = cKDTree(geometry.profile).query(geometry.pitch)
    overlap = roller_radius - np.asarray(distance)      # an array for an array of points
    return _stretches(geometry, overlap > INTERFERENCE_SHARE * roller_radius, overlap, np.max)


def acceleration_jumps(problem: CamProblem) -> tuple[AccelerationJump, ...]:
    """Jumps of the follower's acceleration where one segment meets the next (and at the end of the turn)."""
    segments, starts, levels = problem.segments, segment_starts(problem.segments), segment_levels(problem.segments)
    ends = [segment_motion(s, level, [0.0, s.angle])[2] for s, level in zip(segments, levels, strict=True)]
    scale = max(np.abs(segment_motion(s, level, np.linspace(0, s.angle, 65))[2]).max()
                for s, level in zip(segments, levels, strict=True))
    jumps = []
    for k in range(len(segments)):
        after = (k + 1) % len(segments)
        size = float(ends[after][0] - ends[k][1])
        if abs(size) > JUMP_SHARE * max(scale, np.finfo(float).tiny):
            jumps.append(AccelerationJump(float(starts[k + 1]) if after else 0.0, k, after, size))
    return tuple(jumps)


def check(problem: CamProblem, geometry: CamGeometry) -> CamChecks:
    """Every check of the cam ``geometry`` of ``problem`` (see ``CamChecks``)."""
    roller, base = problem.follower.roller_radius, geometry.base_radius
    convex = geometry.curvature_radius > 0
    step = 2 * np.pi / geometry.angle.size
    if problem.follower.kind == "flat_faced":
        smallest = _smallest(problem, base, geometry, lambda g: g.curvature_radius, np.ones_like(convex))
        cannot_follow = _stretches(geometry, ~convex, geometry.curvature_radius, np.min)
        return CamChecks(pressure=pressure_extremes(problem, geometry), min_pitch_radius=None,
                         min_profile_radius=smallest, min_concave_profile_radius=None,
                         undercut=_with_extreme(cannot_follow, smallest, np.finfo(float).tiny, step), interference=(),
                         acceleration_jumps=acceleration_jumps(problem), pressure_limit=problem.pressure_limit,
                         flat_faced=True, profile_radius_limit=problem.profile_radius_limit)
    smallest_pitch = _smallest(problem, base, geometry, lambda g: g.curvature_radius, convex)
    smallest_profile = None if smallest_pitch is None else Extreme(smallest_pitch.value - roller, smallest_pitch.angle)
    concave = _smallest(problem, base, geometry, lambda g: np.abs(g.profile_curvature_radius), ~convex)
    undercut = _with_extreme(_stretches(geometry, convex & (geometry.curvature_radius < roller),
                                        geometry.curvature_radius, np.min), smallest_pitch, roller, step)
    return CamChecks(pressure=pressure_extremes(problem, geometry), min_pitch_radius=smallest_pitch,
                     min_profile_radius=smallest_profile, min_concave_profile_radius=concave, undercut=undercut,
                     interference=interference(geometry, roller), acceleration_jumps=acceleration_jumps(problem),
                     pressure_limit=problem.pressure_limit, profile_radius_limit=problem.profile_radius_limit)

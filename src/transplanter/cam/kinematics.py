"""The cam evaluated at cam angles: follower motion, roller centre, pitch curve, profile, pressure
angle and curvature radii, all from the generated functions of derivations/cam.py.

The cam turns about the origin by the cam angle theta in the sense ``direction``; the pitch
curve and the profile are given in the cam's own frame (the ground frame at theta = 0).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated import cam as derived_cam
from transplanter._generated.cam import (
    cam_flat_faced,
    cam_oscillating_roller,
    cam_pitch_profile,
    cam_translating_roller,
)
from transplanter.cam.problem import LAWS, CamProblem, Follower, Segment
from transplanter.generated import numpy_twin

#: The derived unit rise of each motion law (``cam_law_<law>``), by law.
_MOTION_LAWS = {law: numpy_twin(getattr(derived_cam, f"cam_law_{law}")) for law in LAWS}


@dataclass(frozen=True)
class CamGeometry:
    """The cam at ``angle`` (N,) rad, for the base radius ``base_radius`` (mm).

    Attributes
    ----------
    segment : ndarray (N,) of int
        Index of the segment each angle falls in.
    motion : ndarray (4, N)
        Follower displacement s, and ds, d2s, d3s per rad of cam (mm or rad of swing).
    center : ndarray (N, 2)
        Roller centre on the ground (mm).
    pitch, profile : ndarray (N, 2)
        Pitch curve and profile in the cam frame (mm).
    pressure_angle : ndarray (N,)
        rad, between the contact normal and the roller centre's direction of motion.
    curvature_radius, profile_curvature_radius : ndarray (N,)
        mm, positive where convex; the profile's is the pitch curve's less the roller radius.
    """

    base_radius: float
    angle: np.ndarray
    segment: np.ndarray
    motion: np.ndarray
    center: np.ndarray
    pitch: np.ndarray
    profile: np.ndarray
    pressure_angle: np.ndarray
    curvature_radius: np.ndarray
    profile_curvature_radius: np.ndarray


def group(*values) -> np.ndarray:
    """One input group of a generated function: scalars and arrays broadcast to one array."""
    return np.array(np.broadcast_arrays(*(np.asarray(v, float) for v in values)))


def segment_starts(segments: tuple[Segment, ...]) -> np.ndarray:
    """Cam angle (rad) at which each segment starts, and a turn at the end: (len + 1,)."""
    return np.concatenate([[0.0], np.cumsum([s.angle for s in segments])])


def segment_levels(segments: tuple[Segment, ...]) -> np.ndarray:
    """Follower level at the start of each segment (mm or rad)."""
    return np.concatenate([[0.0], np.cumsum([s.lift for s in segments])])[:-1]


def segment_motion(segment: Segment, level: float, into) -> np.ndarray:
    """(4, n): s, ds, d2s, d3s at angles ``into`` the segment (rad)."""
    into = np.asarray(into, float)
    if segment.law is None:
        return np.stack([np.full_like(into, level), *np.zeros((3, *into.shape))])
    (motion,) = _MOTION_LAWS[segment.law](group(into, segment.angle, segment.lift, level))
    return motion


def motion_at(segments: tuple[Segment, ...], angle, segment: int | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Follower motion (4, N) at cam angles in [0, 2 pi) and the segment index of each; with ``segment``, every
    angle is taken in that segment (its end included: the limit from inside, where the next segment starts)."""
    angle = np.asarray(angle, float)
    starts, levels = segment_starts(segments), segment_levels(segments)
    if segment is None:
        index = np.clip(np.searchsorted(starts, angle, side="right") - 1, 0, len(segments) - 1)
    else:
        index = np.full(angle.shape, segment)
    motion = np.empty((4, angle.size))
    for k, piece in enumerate(segments):
        mask = index == k
        if mask.any():
            motion[:, mask] = segment_motion(piece, levels[k], angle[mask] - starts[k])
    return motion, index


def oscillating_start(follower: Follower, pitch_radius: float, direction: int) -> tuple[float, float]:
    """Arm angle b0 (rad from +x at the pivot) with the roller centre on the base pitch circle, and the
    sense kappa (+-1) in which a positive swing moves the roller away from the cam centre."""
    pivot, arm = follower.arm
    reach = float(np.hypot(*pivot))
    toward_cam = np.arctan2(-pivot[1], -pivot[0])
    spread = np.arccos(np.clip((reach**2 + arm**2 - pitch_radius**2) / (2 * reach * arm), -1.0, 1.0))
    for start in (toward_cam + spread, toward_cam - spread):
        unit = np.array([np.cos(start), np.sin(start)])
        center = pivot + arm * unit
        surface = direction * np.array([-center[1], center[0]])        # the cam's velocity at the roller
        if (surface @ (pivot - center) > 0) == follower.pulled:
            sense = -np.sign(pivot[0] * unit[1] - pivot[1] * unit[0])
            return float(start), float(sense if sense != 0 else 1.0)
    raise AssertionError("one of the two starts is pulled and the other pushed")


def roller_center(problem: CamProblem, base_radius: float, motion: np.ndarray):
    """Roller centre, its first and second theta-derivatives and its direction of motion, each (2, N)."""
    follower, pitch_radius = problem.follower, base_radius + problem.follower.roller_radius
    if follower.kind == "translating":
        height = np.sqrt(pitch_radius**2 - follower.offset**2)
        return numpy_twin(cam_translating_roller)(group(follower.offset, height), motion[:3])
    start, sense = oscillating_start(follower, pitch_radius, problem.direction)
    pivot, arm = follower.arm
    return numpy_twin(cam_oscillating_roller)(group(*pivot, arm, start, sense), motion[:3])


def _flat_faced(problem: CamProblem, base_radius: float, angle, index, motion) -> CamGeometry:
    """A flat-faced follower has no pitch curve: ``pitch`` holds the profile too, ``center`` the contact point on
    the ground (its x: the offset along the face), the pressure angle is nil."""
    profile, radius, face = numpy_twin(cam_flat_faced)(group(angle, problem.direction, base_radius), motion[:3])
    contact = np.column_stack([face[0], base_radius + motion[0]])
    return CamGeometry(base_radius=base_radius, angle=angle, segment=index, motion=motion, center=contact,
                       pitch=profile.T, profile=profile.T, pressure_angle=np.zeros_like(angle),
                       curvature_radius=radius[0], profile_curvature_radius=radius[0])


def evaluate(problem: CamProblem, base_radius: float, angle=None, segment: int | None = None) -> CamGeometry:
    """The cam of ``problem`` with base circle ``base_radius`` (mm) at cam angles ``angle`` (rad;
    default ``problem.samples`` over a turn); with ``segment``, all in that segment (``motion_at``)."""
    if angle is None:
        angle = np.linspace(0.0, 2 * np.pi, problem.samples, endpoint=False)
    angle = np.atleast_1d(np.asarray(angle, float))
    motion, index = motion_at(problem.segments, angle, segment)
    if problem.follower.kind == "flat_faced":
        return _flat_faced(problem, base_radius, angle, index, motion)
    center, rate, accel, direction = roller_center(problem, base_radius, motion)
    with np.errstate(divide="ignore"):          # a straight stretch of pitch curve has an infinite radius
        pitch, profile, pressure, radii = numpy_twin(cam_pitch_profile)(
            group(angle, problem.direction, problem.follower.roller_radius), center, rate, accel, direction)
    return CamGeometry(base_radius=base_radius, angle=angle, segment=index, motion=motion, center=center.T,
                       pitch=pitch.T, profile=profile.T, pressure_angle=pressure[0], curvature_radius=radii[0],
                       profile_curvature_radius=radii[1])

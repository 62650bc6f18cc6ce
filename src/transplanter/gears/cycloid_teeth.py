"""Incomplete cycloid flanks of the tooth that stands on a corner of the pitch curve (seed 004 sec 2.2).

Between the pitch point A of a flank and the corner J (a zone of pitch arc S), a circle rolls
outside the pitch curve lowered by a depth d; the point it carries rises from A, where it leans
alpha off the normal as the involute below A does, until the circle's contact reaches J
(derivations/cusp.py, ``incomplete_cycloid``: theta from 2 alpha to theta1, r = S / (theta1 - 2 alpha
+ sin 2 alpha), d = r (1 - cos 2 alpha)). The contact climbs the arch with a pressure angle from
alpha to theta1 / 2, which the pair meets as the corner passes the line of centres. The rolling
uses the frame of the corner's own side (``segment_frame``), continued past the corner.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.gears.composite_curve import CompositeCurve, segment_frame
from transplanter.generated import numpy_twin

_trace = numpy_twin("cusp", "cycloid_trace")
_incomplete = numpy_twin("cusp", "incomplete_cycloid")
#: Points per arch.
ARCH_POINTS = 400


@dataclass(frozen=True)
class CycloidArch:
    """One incomplete cycloid flank, from the pitch point to the top of its arch over the corner (mm, rad)."""

    points: np.ndarray          # (ARCH_POINTS, 2), pitch point first
    radius: float               # rolling radius r
    depth: float                # the rolling base below the pitch curve
    top_height: float           # last point's height above the pitch curve (straight base)
    start_angle: float          # theta0 = 2 alpha
    contact_arc: np.ndarray     # pitch arc (mm, the design's arc length) of the rolling contact at each point
    theta: np.ndarray           # the circle's turn at each point (rad)
    normals: np.ndarray         # outward normal of the rolling base at each point's contact


def arch(curve: CompositeCurve, arc_to_phi, corner_arc: float, zone: float, segment: int, side: int,
         alpha: float, end_angle: float) -> CycloidArch:
    """The arch over ``zone`` (mm of pitch arc) before the corner (``side`` +1, rising towards larger arc)
    or after it (-1), rolling on ``segment`` up to ``end_angle`` (theta1, rad); ``arc_to_phi`` maps the
    design's arc length to the angle."""
    theta0, radius, depth, top = (float(v[0]) for v in _incomplete([alpha], [zone], [end_angle]))
    theta = np.linspace(theta0, end_angle, ARCH_POINTS)
    contact = corner_arc - side * radius * (end_angle - theta)    # arc rolled back from the corner
    point, tangent, normal = segment_frame(curve, segment, arc_to_phi(contact))
    base = point - depth * normal
    angle = np.arctan2(tangent[:, 1], tangent[:, 0])
    (x, y), = _trace(base.T, [angle], [np.full_like(theta, radius)], [theta], [np.full_like(theta, float(side))])
    return CycloidArch(np.c_[x, y], radius, depth, top, theta0, contact, theta, normal)


def arch_pressure_range(arch: CycloidArch) -> tuple[float, float]:
    """Smallest and largest angle (deg) between the arch's tangent and its base's normal (theta / 2 on a line)."""
    tangent = np.gradient(arch.points, arch.theta, axis=0)
    cosine = np.abs(np.sum(tangent * arch.normals, axis=1)) / np.linalg.norm(tangent, axis=1)
    lean = np.degrees(np.arccos(np.clip(cosine, 0.0, 1.0)))
    return float(lean.min()), float(lean.max())


def arch_min_curvature_radius(arch: CycloidArch) -> float:
    """Smallest radius of curvature (mm) along the arch (4 r sin(theta / 2) on a line), by differences in theta."""
    first = np.gradient(arch.points, arch.theta, axis=0)
    second = np.gradient(first, arch.theta, axis=0)
    cross = np.abs(first[:, 0] * second[:, 1] - first[:, 1] * second[:, 0])
    return float((np.linalg.norm(first, axis=1) ** 3 / cross)[1:-1].min())

"""Incomplete cycloid flanks of the tooth that stands on a corner of the pitch curve (the cusp-pitch-curve
paper, section 2.2).

From the pitch point A of a flank the tooth rises straight, leaning alpha as a rack's flank does, to
the joint where a circle rolling outside the pitch curve carries a point that leans alpha too
(theta0 = 2 alpha). From there the circle rolls on the pitch curve itself: its contact reaches the
corner J, a zone S after A, when it has turned theta_J, pivots about J through the tangent's turn and
rolls on along the next segment until the point reaches the tip (derivations/cusp.py,
``incomplete_cycloid``: r = S / (theta_J - 2 alpha + 2 tan alpha)). The normal of the arch always
passes through the rolling contact on the pitch curve, so the arch is conjugate to its envelope and
drives past the corner; the contact meets it with pressure angle theta / 2, theta_J / 2 as the
corner passes the line of centres.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.cusp import cycloid_trace, incomplete_cycloid
from transplanter.gears.composite_curve import CompositeCurve, segment_frame
from transplanter.generated import numpy_twin

_trace = numpy_twin(cycloid_trace)
_incomplete = numpy_twin(incomplete_cycloid)
#: Points per arch (rolling, pivot) and on the straight flank below it.
ARCH_POINTS, PIVOT_POINTS, STRAIGHT_POINTS = 600, 60, 20


@dataclass(frozen=True)
class CycloidArch:
    """One flank of a corner tooth from its pitch point A over the corner to past the tip (mm, rad)."""

    points: np.ndarray          # pitch point A first, the straight flank, then the arch
    radius: float               # rolling radius r
    joint_height: float         # where the arch meets the straight flank, above the pitch curve
    corner_height: float        # the arch's point as the circle pivots on the corner (straight base)
    start_angle: float          # theta0 = 2 alpha
    corner_angle: float         # theta_J, the circle's turn when it reaches the corner
    contact_arc: np.ndarray     # pitch arc (mm) of the rolling contact at each arch point
    theta: np.ndarray           # the circle's turn at each arch point (rad)


def _rolled(curve, arc_to_phi, segment, contact, theta, radius, side):
    point, tangent, _ = segment_frame(curve, segment, arc_to_phi(contact))
    angle = np.arctan2(tangent[:, 1], tangent[:, 0])
    return _roulette(point, angle, radius, theta, side)


def _roulette(point, angle, radius, theta, side):
    (x, y), = _trace(point.T, [angle], [np.full_like(theta, radius)], [theta], [np.full_like(theta, float(side))])
    return np.c_[x, y]


def arch(curve: CompositeCurve, arc_to_phi, corner_arc: float, zone: float, segments: tuple[int, int], side: int,
         alpha: float, corner_angle: float) -> CycloidArch:
    """The flank whose pitch point lies ``zone`` (mm of pitch arc) before the corner (``side`` +1, rising towards
    larger arc) or after it (-1); ``segments`` are the segment on its own side of the corner and the one beyond;
    ``corner_angle`` is theta_J (rad); ``arc_to_phi`` maps the design's arc length to the angle."""
    theta0, radius, cusp, joint, over_corner = (float(v[0]) for v in _incomplete([alpha], [zone], [corner_angle]))
    start = corner_arc - side * zone
    theta = np.linspace(theta0, np.pi, ARCH_POINTS)
    contact = start + side * (cusp + radius * theta)
    near = side * (contact - corner_arc) <= 0
    own, beyond = segments
    pivot_from, pivot_to = (np.arctan2(t[0, 1], t[0, 0]) for t in
                            (segment_frame(curve, k, arc_to_phi(np.array([corner_arc])))[1] for k in (own, beyond)))
    turn = np.angle(np.exp(1j * (pivot_to - pivot_from)))
    corner_point = segment_frame(curve, own, arc_to_phi(np.array([corner_arc])))[0]
    pivot = pivot_from + np.linspace(0.0, 1.0, PIVOT_POINTS) * turn
    rolled = [_rolled(curve, arc_to_phi, own, contact[near], theta[near], radius, side),
              _roulette(np.repeat(corner_point, PIVOT_POINTS, axis=0), pivot, radius,
                        np.full(PIVOT_POINTS, corner_angle), side),
              _rolled(curve, arc_to_phi, beyond, contact[~near], theta[~near], radius, side)]
    pitch_point = segment_frame(curve, own, arc_to_phi(np.array([start])))[0][0]
    fractions = np.linspace(0.0, 1.0, STRAIGHT_POINTS, endpoint=False)[:, None]
    straight = pitch_point + fractions * (rolled[0][0] - pitch_point)
    return CycloidArch(np.concatenate([straight, *rolled]), radius, joint, over_corner, theta0, corner_angle,
                       np.r_[contact[near], np.full(PIVOT_POINTS, corner_arc), contact[~near]],
                       np.r_[theta[near], np.full(PIVOT_POINTS, corner_angle), theta[~near]])


def corner_heights(zone: float, alpha: float, corner_angles: float | np.ndarray) -> np.ndarray:
    """Height (mm, above a straight pitch line) of the arch's point as its circle reaches the corner,
    for each theta_J."""
    angles = np.atleast_1d(np.asarray(corner_angles, float))
    return _incomplete([np.full_like(angles, alpha)], [np.full_like(angles, zone)], [angles])[4][0]


def arch_pressure_range(arch: CycloidArch, used: int) -> tuple[float, float]:
    """Pressure angle (deg) at the first and last of the ``used`` arch points (the arch as cut at the tip): the
    arch's normal makes theta / 2 with the pitch curve's tangent at the rolling contact (derivations/cusp.py)."""
    theta = arch.theta[:max(1, used)]
    return float(np.degrees(theta[0] / 2)), float(np.degrees(theta[-1] / 2))


def polyline_min_curvature_radius(points: np.ndarray) -> float:
    """Smallest radius (mm) of the circles through three consecutive points of a polyline."""
    a, b, c = points[:-2], points[1:-1], points[2:]
    ab, bc, ca = (np.linalg.norm(q - p, axis=1) for p, q in ((a, b), (b, c), (c, a)))
    cross = np.abs((b - a)[:, 0] * (c - a)[:, 1] - (b - a)[:, 1] * (c - a)[:, 0])
    keep = cross > 0
    return float(np.min(ab[keep] * bc[keep] * ca[keep] / (2 * cross[keep])))

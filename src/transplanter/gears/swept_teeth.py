"""Tooth outlines by numerical envelope: what a moving cutter leaves of a gear blank (seed 004, seed 001).

The gear blank is bounded by its tip curve (the pitch curve offset by one module). A cutter
outline is carried through its rolling positions; on every ray from the gear's center, the
gear keeps material only below the smallest radius any cutter point reaches on that ray.
Flanks, root fillets (the trochoids of the cutter's tip corners) and undercut all follow,
with no case analysis. Polar angle is cut into fine bins, each keeping the smallest radius the
swept cutter reaches in its wedge, so the outline is star-shaped about the gear center by
construction. That radius is computed exactly on the segments that bound the swept region (the
cutter's edges at each position and its vertices' chords between positions), so positions can be
a tenth of a module apart and no bin is missed between sample points.

Two uses:
- a shaper cutter (an involute pinion, here a rack-cut circular gear with a 1.25-module
  addendum) whose pitch circle rolls without slip on the pitch curve, center on the normal;
- the mate of a cut gear, swept by that gear's outline in the pair's relative motion, which
  makes the pair conjugate (two shaper-cut non-circular gears would not be).
"""
from __future__ import annotations

import numpy as np
import shapely

from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.geometry.poses import rotate_about
from transplanter.gears.rack_teeth import ADDENDUM, DEDENDUM, PitchTable, orientation, pitch_table, rack_profile

ORIGIN = (0.0, 0.0)

#: Polar bins per turn: about 0.01 deg, a few micrometres of arc at gear sizes.
BINS = 36000
#: A cut outline that cuts its mate is first simplified (Douglas-Peucker) within this many modules.
SIMPLIFY_MODULES = 1e-4


def shaper_cutter(module: float, alpha: float, teeth: int) -> np.ndarray:
    """Outline of an involute pinion cutter, teeth 1.25 modules high, tooth 0 centered on +x."""
    radius = module * teeth / 2
    angle = np.linspace(0, 2 * np.pi, 20 * teeth * 8 + 1)
    table = pitch_table(radius * np.c_[np.cos(angle), np.sin(angle)], radius * angle,
                        np.c_[-np.sin(angle), np.cos(angle)])
    return rack_profile(table, teeth, module, alpha, addendum=DEDENDUM, dedendum=DEDENDUM)


def _polar(points: np.ndarray):
    """Polar angle (rad, -pi to pi) and squared radius of points (..., 2)."""
    return np.arctan2(points[..., 1], points[..., 0]), points[..., 0] ** 2 + points[..., 1] ** 2


def _segments(points: np.ndarray, facing: np.ndarray, reach: float, place, chunk: int = 24):
    """Points and the segments between them (index pairs) bounding the region that ``points``, a closed
    outline, sweeps through its positions (``place(points, rows) -> (rows, W, 2)``), a chunk at a time.

    Between positions k and k + 1 that region is the outline at k together with the quadrilaterals
    its edges sweep: its boundary lies on the edges at k and on each vertex's chord from k to k + 1
    (the fold inside a swept edge, where the envelope touches, is met to second order in the step).
    Only the vertices whose polar angle (own frame) is within ``reach`` of ``facing`` take part.
    """
    angle, _ = _polar(points)
    last = len(facing) - 1
    for first in range(0, last, chunk):
        rows = np.arange(first, min(first + chunk, last) + 1)
        middle = (facing[rows].max() + facing[rows].min()) / 2
        half = (facing[rows].max() - facing[rows].min()) / 2 + reach
        near = np.abs(np.mod(angle - middle + np.pi, 2 * np.pi) - np.pi) <= half
        index = np.flatnonzero(near)
        edge = np.flatnonzero(near & np.roll(near, -1))
        cloud = place(points[index], rows)                          # (rows, W, 2)
        width = len(index)
        row = width * np.arange(len(rows) - (rows[-1] != last))[:, None]  # the last position also keeps its edges
        at = np.searchsorted(index, edge)
        after = np.searchsorted(index, (edge + 1) % len(points))
        still = np.arange(width * (len(rows) - 1))
        yield cloud.reshape(-1, 2), np.r_[(row + at).ravel(), still], np.r_[(row + after).ravel(), still + width]


def _lower_envelope(points: np.ndarray, tip: np.ndarray, segments) -> np.ndarray:
    """Blank tip curve cut down by every segment in ``segments`` (all in the gear frame).

    Each bin keeps the smallest radius any segment reaches within its wedge, computed exactly: at
    the segment's ends, where it crosses the wedge's edge rays, and at its point nearest the center.
    """
    width = 2 * np.pi / BINS
    edges = -np.pi + width * np.arange(BINS)
    edge_rays = np.c_[np.cos(edges), np.sin(edges)]
    centers = edges + width / 2
    tip_angle, tip_squared = _polar(tip)
    order = np.argsort(tip_angle)
    radius = np.interp(centers, tip_angle[order], np.sqrt(tip_squared[order]), period=2 * np.pi)
    block = 60                                              # bins per block of the coarse maximum
    for points_at, a, b in segments:
        angle, squared = _polar(points_at)
        start = points_at[a]
        direction = points_at[b] - start
        length = np.maximum(direction[:, 0] ** 2 + direction[:, 1] ** 2, 1e-300)
        along = -(start[:, 0] * direction[:, 0] + start[:, 1] * direction[:, 1]) / length
        foot = start + np.clip(along, 0.0, 1.0)[:, None] * direction
        nearest = foot[:, 0] ** 2 + foot[:, 1] ** 2
        turn = np.mod(angle[b] - angle[a] + np.pi, 2 * np.pi) - np.pi
        low = np.minimum(angle[a], angle[a] + turn)
        first = np.floor((low + np.pi) / width).astype(int)
        count = np.floor((low + np.abs(turn) + np.pi) / width).astype(int) - first     # edge rays crossed
        # a segment that nowhere comes nearer the center than the highest bin where it lies cuts nothing
        highest = radius.reshape(-1, block).max(axis=1)
        blocks = len(highest)
        reach = np.maximum(highest[(first // block) % blocks], highest[((first + count) // block) % blocks])
        keep = (nearest < reach ** 2) | (count >= block)
        a, b, start, direction, first, count = a[keep], b[keep], start[keep], direction[keep], first[keep], count[keep]
        ends = np.r_[a, b]
        np.minimum.at(radius, np.minimum(((angle[ends] + np.pi) / width).astype(int), BINS - 1), np.sqrt(squared[ends]))
        inner = (along[keep] > 0) & (along[keep] < 1)
        foot_angle, foot_squared = _polar(foot[keep][inner])
        np.minimum.at(radius, np.minimum(((foot_angle + np.pi) / width).astype(int), BINS - 1), np.sqrt(foot_squared))
        segment = np.repeat(np.arange(len(first)), count)
        index = (first[segment] + 1 + np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)) % BINS
        d, p = direction[segment], start[segment]
        # r e x d = p x d at the crossing r e = p + u d of the edge ray e with the segment p + u d
        across = edge_rays[index, 0] * d[:, 1] - edge_rays[index, 1] * d[:, 0]
        moment = p[:, 0] * d[:, 1] - p[:, 1] * d[:, 0]
        crossing = moment / np.where(across == 0, 1.0, across)
        valid = across != 0
        np.minimum.at(radius, np.r_[index[valid], (index[valid] - 1) % BINS], np.r_[crossing[valid], crossing[valid]])
    outline = radius[:, None] * np.c_[np.cos(centers), np.sin(centers)]
    return outline if orientation(points) > 0 else outline[::-1]


def shaper_profile(table: PitchTable, module: float, alpha: float, cutter_teeth: int,
                   first_tooth_at: float = 0.0, step: float | None = None) -> np.ndarray:
    """Outline cut by a shaper rolling on the pitch curve; gear tooth k centered at first_tooth_at + k p.

    ``step`` (mm, default module / 10) spaces the cutter's positions along the pitch curve, shortened
    so that a whole number of them fills a pitch.
    """
    step = step or module / 10
    radius = module * cutter_teeth / 2
    cutter = shaper_cutter(module, alpha, cutter_teeth)
    o = table.orientation
    pitch = np.pi * module
    # whole positions per pitch, one with the cutter centred in every tooth space (the root's deepest point)
    spacing = pitch / np.ceil(pitch / step)
    s = first_tooth_at + pitch / 2 + np.r_[np.arange(0.0, table.perimeter - spacing / 2, spacing), table.perimeter]
    contact, _, normal = table.at(s)
    center = contact + radius * normal
    psi = np.arctan2(-normal[:, 1], -normal[:, 0])
    # cutter tooth 0 (local angle 0) sits in the gear's tooth space at first_tooth_at + p/2
    turn = np.unwrap(psi) + o * (s - first_tooth_at - pitch / 2) / radius
    local_facing = np.unwrap(psi) - turn
    reach = 2.5 * (ADDENDUM + DEDENDUM) * module / radius

    def place(points, rows):
        return center[rows, None, :] + rotate_about(points[None], ORIGIN, turn[rows, None])

    tip = table.points + ADDENDUM * module * table.normals
    return _lower_envelope(table.points, tip, _segments(cutter, local_facing, reach, place))


def mate_profile(design: GearPairDesign, driver_outline: np.ndarray, driven: PitchTable, module: float,
                 step: float | None = None) -> np.ndarray:
    """Driven outline left by the driver's teeth in the pair's relative motion (conjugate by construction).

    ``step`` (mm, default module / 10) is the most driver pitch arc between two positions.
    """
    step = step or module / 10
    n1, n2 = design.orders
    phi1 = np.r_[np.arange(0.0, 2 * np.pi * n2 / n1, step / design.radius[0].max()), 2 * np.pi * n2 / n1]
    reach = 2.5 * (ADDENDUM + DEDENDUM) * module / design.radius[0].min()
    phi2 = driven_angle(design, phi1)

    def place(points, rows):
        world = rotate_about(points[None], ORIGIN, -phi1[rows, None])            # driver points near the line of centres
        return rotate_about(world - [design.center_distance, 0.0], ORIGIN, -phi2[rows, None])

    # the driver's one-per-bin vertices, thinned where they stay within a hair of their chords
    ring = shapely.simplify(shapely.linearrings(driver_outline), SIMPLIFY_MODULES * module)
    cutter = shapely.get_coordinates(ring)[:-1]
    tip = driven.points + ADDENDUM * module * driven.normals
    return _lower_envelope(driven.points, tip, _segments(cutter, phi1, reach, place))

"""Tooth outlines by numerical envelope: what a moving cutter leaves of a gear blank (seed 004, seed 001).

The gear blank is bounded by its tip curve (the pitch curve offset by one module). A cutter
outline is carried through its rolling positions; on every ray from the gear's center, the
gear keeps material only below the smallest radius any cutter point reaches on that ray.
Flanks, root fillets (the trochoids of the cutter's tip corners) and undercut all follow,
with no case analysis. Rays are binned finely in polar angle, so the outline is star-shaped
about the gear center by construction.

Two uses:
- a shaper cutter (an involute pinion, here a rack-cut circular gear with a 1.25-module
  addendum) whose pitch circle rolls without slip on the pitch curve, center on the normal;
- the mate of a cut gear, swept by that gear's outline in the pair's relative motion, which
  makes the pair conjugate (two shaper-cut non-circular gears would not be).
"""
from __future__ import annotations

import numpy as np

from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.geometry.poses import rotate_about
from transplanter.gears.rack_teeth import ADDENDUM, DEDENDUM, PitchTable, orientation, pitch_table, rack_profile

ORIGIN = (0.0, 0.0)

#: Polar bins per turn: about 0.01 deg, a few micrometres of arc at gear sizes.
BINS = 36000


def shaper_cutter(module: float, alpha: float, teeth: int) -> np.ndarray:
    """Outline of an involute pinion cutter, teeth 1.25 modules high, tooth 0 centered on +x."""
    radius = module * teeth / 2
    angle = np.linspace(0, 2 * np.pi, 20 * teeth * 8 + 1)
    table = pitch_table(radius * np.c_[np.cos(angle), np.sin(angle)], radius * angle,
                        np.c_[-np.sin(angle), np.cos(angle)])
    return rack_profile(table, teeth, module, alpha, addendum=DEDENDUM, dedendum=DEDENDUM)


def _by_angle(points: np.ndarray):
    """Sort points by polar angle, for picking those facing a direction."""
    angle = np.arctan2(points[:, 1], points[:, 0])
    order = np.argsort(angle)
    return points[order], angle[order]


def _facing(sorted_angle, low: float, high: float):
    """Indices of points whose polar angle lies in [low, high] (cyclic, radians)."""
    n = len(sorted_angle)
    start = np.searchsorted(sorted_angle, np.mod(low + np.pi, 2 * np.pi) - np.pi)
    width = int(np.ceil(n * (high - low) / (2 * np.pi))) + 2
    return (start + np.arange(width)) % n


def _swept(points: np.ndarray, sorted_angle, facing: np.ndarray, reach: float, place, refine: int = 4):
    """Point clouds of ``points`` placed at every position (``place(points, rows) -> (rows, W, 2)``).

    Positions go in chunks that share the same material points, so each point's path between
    two positions can be filled in by ``refine`` linear steps (a chord of a short arc).
    """
    chunk = 64
    for start in range(0, len(facing) - 1, chunk):
        rows = np.arange(start, min(start + chunk + 1, len(facing)))
        index = _facing(sorted_angle, facing[rows].min() - reach, facing[rows].max() + reach)
        cloud = place(points[index], rows)                      # (rows, W, 2)
        steps = np.linspace(0, 1, refine, endpoint=False)[None, :, None, None]
        between = cloud[:-1, None] + steps * (cloud[1:, None] - cloud[:-1, None])
        yield between.reshape(-1, 2)


def _lower_envelope(points: np.ndarray, tip: np.ndarray, chunks: list[np.ndarray]) -> np.ndarray:
    """Blank tip curve cut down by every point cloud in ``chunks`` (all in the gear frame)."""
    bins = np.linspace(-np.pi, np.pi, BINS + 1)
    tip_angle = np.arctan2(tip[:, 1], tip[:, 0])
    order = np.argsort(tip_angle)
    centers = (bins[:-1] + bins[1:]) / 2
    radius = np.interp(centers, tip_angle[order], np.hypot(*tip[order].T), period=2 * np.pi)
    for cloud in chunks:
        index = np.minimum(((np.arctan2(cloud[:, 1], cloud[:, 0]) + np.pi) * (BINS / (2 * np.pi))).astype(int), BINS - 1)
        np.minimum.at(radius, index, np.hypot(cloud[:, 0], cloud[:, 1]))
    outline = radius[:, None] * np.c_[np.cos(centers), np.sin(centers)]
    return outline if orientation(points) > 0 else outline[::-1]


def _densify(outline: np.ndarray, step: float) -> np.ndarray:
    """Points along a closed outline no farther apart than ``step``."""
    edges = np.roll(outline, -1, axis=0) - outline
    counts = np.maximum(1, np.ceil(np.linalg.norm(edges, axis=1) / step).astype(int))
    segment = np.repeat(np.arange(len(outline)), counts)
    fraction = (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)) / counts[segment]
    return outline[segment] + fraction[:, None] * edges[segment]


def shaper_profile(table: PitchTable, module: float, alpha: float, cutter_teeth: int,
                   first_tooth_at: float = 0.0, step: float | None = None) -> np.ndarray:
    """Outline cut by a shaper rolling on the pitch curve; gear tooth k centered at first_tooth_at + k p."""
    step = step or module / 40
    radius = module * cutter_teeth / 2
    cutter, cutter_angle = _by_angle(_densify(shaper_cutter(module, alpha, cutter_teeth), step / 2))
    o = table.orientation
    pitch = np.pi * module
    s = np.r_[np.arange(0.0, table.perimeter, step), table.perimeter]
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
    return _lower_envelope(table.points, tip, _swept(cutter, cutter_angle, local_facing, reach, place))


def mate_profile(design: GearPairDesign, driver_outline: np.ndarray, driven: PitchTable, module: float,
                 step: float | None = None) -> np.ndarray:
    """Driven outline left by the driver's teeth in the pair's relative motion (conjugate by construction)."""
    step = step or module / 40
    n1, n2 = design.orders
    outline, outline_angle = _by_angle(_densify(driver_outline, step / 2))
    phi1 = np.r_[np.arange(0.0, 2 * np.pi * n2 / n1, step / design.radius[0].max()), 2 * np.pi * n2 / n1]
    reach = 2.5 * (ADDENDUM + DEDENDUM) * module / design.radius[0].min()
    phi2 = driven_angle(design, phi1)

    def place(points, rows):
        world = rotate_about(points[None], ORIGIN, -phi1[rows, None])            # driver points near the line of centres
        return rotate_about(world - [design.center_distance, 0.0], ORIGIN, -phi2[rows, None])

    tip = driven.points + ADDENDUM * module * driven.normals
    return _lower_envelope(driven.points, tip, _swept(outline, outline_angle, phi1, reach, place))

"""Tooth outlines by numerical envelope: what a moving cutter leaves of a gear blank (the cusp-pitch-curve
and onion-transplanter papers).

The gear blank reaches one module above the pitch curve. A cutter outline is carried through
its rolling positions; along every normal of the pitch curve the gear keeps material only below
the lowest height any cutter point reaches on it. Flanks, root fillets (the trochoids of the
cutter's tip corners) and undercut all follow, with no case analysis. Arc length along the pitch
curve is cut into fine bins, each keeping the lowest height the swept cutter reaches over it.
Binned along the normals, not along the radii: on a non-circular gear a tooth leans off its
radius, and polar bins (the lowest radius on each ray from the centre) cut away the flank beneath
the lean, losing contact once per tooth there (0.04 mm of transmission error on the shaper test
pair). Heights are taken on the segments that bound the swept region (the cutter's edges at each
position and its vertices' chords between positions), at their ends and wherever they cross a
bin's edge, so positions can be a tenth of a module apart and no bin is missed between them.
Each point's (s, h) is the foot of its normal on the pitch curve, converged by Newton's method
(``PitchTable.normal_coordinates``) from where the ray through the gear's centre meets the curve.

Two uses:
- a shaper cutter (an involute pinion with a 1.25-module addendum, ``pinion_cutter``) whose pitch
  circle rolls without slip on the pitch curve, center on the normal;
- the mate of a cut gear, swept by that gear's outline in the pair's relative motion, which
  makes the pair conjugate (two shaper-cut non-circular gears would not be).
"""
from __future__ import annotations

import contextlib
from collections.abc import Iterator
from contextvars import ContextVar
from functools import partial

import numpy as np
import shapely

from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.gears.pinion_cutter import shaper_cutter
from transplanter.gears.rack_teeth import ADDENDUM, DEDENDUM, PitchTable
from transplanter.geometry.outline_thinning import thinned
from transplanter.geometry.planar import DIAMOND_TURN, diamond_angle, modulo
from transplanter.side_process import Twin

#: Width of the pitch-arc bins (modules): a few micrometres at gear sizes.
BIN_MODULES = 0.002
#: Cutter points farther than this (modules) beyond the blank's tip are left out.
MARGIN_MODULES = 0.1
#: A cut outline that cuts its mate is first simplified (Douglas-Peucker) within this many modules.
SIMPLIFY_MODULES = 1e-4
#: Most a straight cutter edge may bow (modules) in the normal coordinates of the gear it cuts.
BOW_MODULES = 1e-4
#: The foot of a point's normal on the pitch curve is found to this many modules of arc.
CONVERGED_MODULES = 1e-12
#: Segments cut a block at a time (the block's arrays stay in cache).
SEGMENT_BLOCK = 16384
#: Levels of run maxima that decide whether a segment can cut (runs of up to 2^(levels - 1) bins).
RUN_LEVELS = 11
#: The level of run maxima for a segment crossing n bin edges: floor(log2(n + 1)), at most RUN_LEVELS - 1 (taken
#: clipped, for any n).
_RUN_LEVEL = np.minimum(np.floor(np.log2(np.arange(1, 2 ** RUN_LEVELS + 1))), RUN_LEVELS - 1).astype(np.intp)

#: The twin process cutting the same envelopes in step (``shared_with``), or None.
_twin: ContextVar[Twin | None] = ContextVar("twin", default=None)


@contextlib.contextmanager
def shared_with(twin: Twin | None) -> Iterator[None]:
    """Within it, each envelope is cut half here and half by ``twin``'s other process, which cuts the same envelopes
    in the same order (``side_process.twinned``), to the outline one process cuts; with None, all here."""
    token = _twin.set(twin)
    try:
        yield
    finally:
        _twin.reset(token)


def _polar(points: np.ndarray):
    """Diamond angle (``planar.diamond_angle``, -1 to 3, in the order of the polar angle) and squared radius of
    points (..., 2)."""
    x, y = points[..., 0], points[..., 1]
    return diamond_angle(x, y), x * x + y * y


def _rigid_placement(turn: np.ndarray, offset: np.ndarray):
    """``place(points, rows) -> (rows, W, 2)`` for ``_positions``: points turned by ``turn[k]`` (rad, ccw) about the
    origin, then moved by ``offset[k]`` (mm), at each position k of ``rows``."""
    cos, sin = np.cos(turn), np.sin(turn)

    def place(points: np.ndarray, rows: np.ndarray) -> np.ndarray:
        x, y = points[:, 0], points[:, 1]
        c, s = cos[rows, None], sin[rows, None]
        placed = np.empty((len(rows), len(points), 2))
        placed[..., 0] = c * x - s * y + offset[rows, 0, None]
        placed[..., 1] = s * x + c * y + offset[rows, 1, None]
        return placed

    return place


def _positions(points: np.ndarray, facing: np.ndarray, reach: float, place, share: tuple[int, int] = (0, 1),
               chunk: int = 24):
    """``points``, a closed outline, placed at its positions (``place(points, rows) -> (rows, W, 2)``) a chunk of
    positions at a time, with the outline's edges among the placed vertices: the flat indices (into rows x W) of
    both ends of each edge the chunk keeps. Chunks share their last and first rows, whose edges count once, in
    the later chunk. ``share`` = (part, parts): the chunks of that part of as many runs of consecutive chunks.

    Between positions k and k + 1 the region the outline sweeps is the outline at k together with the
    quadrilaterals its edges sweep: its boundary lies on the edges at k and on each vertex's chord from k to
    k + 1 (the fold inside a swept edge, where the envelope touches, is met to second order in the step).
    Only the vertices whose polar angle (own frame) is within ``reach`` of ``facing`` take part.
    """
    angle = np.arctan2(points[:, 1], points[:, 0])
    last = len(facing) - 1
    starts = range(0, last, chunk)
    part, parts = share
    for first in starts[len(starts) * part // parts:len(starts) * (part + 1) // parts]:
        rows = np.arange(first, min(first + chunk, last) + 1)
        middle = (facing[rows].max() + facing[rows].min()) / 2
        half = (facing[rows].max() - facing[rows].min()) / 2 + reach
        near = np.abs(modulo(angle - middle + np.pi, 2 * np.pi) - np.pi) <= half
        index = np.flatnonzero(near)
        edge = np.flatnonzero(near & np.append(near[1:], near[0]))
        edged = len(rows) - (rows[-1] != last)          # the last position also keeps its edges
        row_start = len(index) * np.arange(edged)[:, None]
        yield (place(points[index], rows), (row_start + np.searchsorted(index, edge)).ravel(),
               (row_start + np.searchsorted(index, (edge + 1) % len(points))).ravel())


def _short_edges(outline: np.ndarray, table: PitchTable, module: float) -> np.ndarray:
    """The cutter outline with its edges split so none bows more than ``BOW_MODULES`` in the gear's normal
    coordinates: a straight edge of length L over a pitch curve of curvature kappa is a parabola of
    sagitta L^2 |kappa| / 8 in (s, h), and ``_lower_envelope`` takes edges as straight there. A long flat
    edge (a tooth tip on a nearly straight stretch of the cutting gear) otherwise leaves material in the
    mate's root where the tip passed."""
    turn = np.abs(np.diff(np.unwrap(np.arctan2(table.tangents[:, 1], table.tangents[:, 0]))))
    kappa = float(np.max(turn / np.maximum(np.diff(table.arc), 1e-300)))
    longest = np.sqrt(8 * BOW_MODULES * module / max(kappa, 1e-12 / module))
    ring = shapely.segmentize(shapely.linearrings(outline), longest)
    return shapely.get_coordinates(ring)[:-1]


def _radial_arc(table: PitchTable):
    """Arc length on the pitch curve of a direction (its diamond angle, ``_polar``): where the ray that way meets
    the curve (a pitch curve turns about its centre, so each ray meets it once), interpolated between the samples.
    Near the curve this is close to the foot of a point's normal, a start for ``PitchTable.normal_coordinates``."""
    angle = table.orientation * np.unwrap(_polar(table.points)[0], period=DIAMOND_TURN)

    def arc(direction: np.ndarray) -> np.ndarray:
        return np.interp(angle[0] + modulo(table.orientation * direction - angle[0], DIAMOND_TURN), angle, table.arc)

    return arc


def _run_maxima(values: np.ndarray, levels: int) -> np.ndarray:
    """Row k: the largest of each run of 2^k values starting at every index (where the run passes the end of the
    values, +inf), k = 0 .. ``levels`` - 1."""
    runs = np.empty((levels, len(values)))
    runs[0] = values
    for k in range(1, levels):
        half = 2 ** (k - 1)
        np.maximum(runs[k - 1, :-half], runs[k - 1, half:], out=runs[k, :-half])
        runs[k, -half:] = np.inf
    return runs


def _cut(at_edge: np.ndarray, lowest: np.ndarray, width: float, perimeter: float, ends: np.ndarray):
    """Lower ``at_edge``, the lowest height met on each bin edge (edge k at arc k ``width`` round a pitch curve
    of ``perimeter``), to the segments with ends (s, h) = ``ends`` = (s_a, h_a, s_b, h_b) (rows) where they cross
    it. A segment that stays at or above ``lowest``, a height each bin already reaches (bin k between edges k and
    k + 1), over every bin its crossed edges bound lowers none of them and is passed over: ``lowest``'s run
    maxima (``_run_maxima``) give the largest over those bins from two overlapping runs, for segments over fewer
    than ``2 ** RUN_LEVELS`` bins that do not pass the end of the curve (the rest are all cut)."""
    count = len(lowest)
    runs = _run_maxima(lowest, RUN_LEVELS)
    for block in range(0, ends.shape[1], SEGMENT_BLOCK):
        s_a, h_a, s_b, h_b = ends[:, block:block + SEGMENT_BLOCK]
        run = modulo(s_b - s_a + perimeter / 2, perimeter) - perimeter / 2   # the short way round
        back = run < 0
        start = np.where(back, s_b, s_a)
        run = np.abs(run)
        first = np.floor(start / width).astype(int)
        crossed = np.floor((start + run) / width).astype(int) - first     # bin edges crossed
        low = np.mod(first, count)                                         # bins low to low + crossed
        level = _RUN_LEVEL.take(crossed, mode="clip")
        high = np.minimum(low + crossed - np.left_shift(1, level) + 1, count - 1)  # inf where past the end
        row = level * count
        reached = np.maximum(runs.take(row + low), runs.take(row + high))
        some = np.flatnonzero((crossed > 0) & ((crossed >= 2 ** RUN_LEVELS - 1) | (np.minimum(h_a, h_b) < reached)))
        back, h_a, h_b = back[some], h_a[some], h_b[some]
        h_a, h_b = np.where(back, h_b, h_a), np.where(back, h_a, h_b)
        slope = (h_b - h_a) / run[some]                                    # run > 0 where an edge is crossed
        start, first, crossed = start[some], first[some], crossed[some]
        edge = np.arange(crossed.sum()) + np.repeat(first + 1 - (np.cumsum(crossed) - crossed), crossed)
        np.minimum.at(at_edge, edge % count, np.repeat(h_a, crossed) + (edge * width - np.repeat(start, crossed))
                      * np.repeat(slope, crossed))


def _with_segment_ends(near: np.ndarray, first_ends: np.ndarray, second_ends: np.ndarray) -> np.ndarray:
    """``near`` (positions x vertices, from ``_positions``) grown by both ends of every segment that may cut: an
    edge (flat indices of its ends ``first_ends``, ``second_ends``) or a vertex's chord to the next position,
    with one end near."""
    flat = near.ravel()
    touching = np.flatnonzero(flat.take(first_ends) | flat.take(second_ends))
    chord = near[:-1] | near[1:]
    grown = near.copy()
    grown.ravel()[first_ends.take(touching)] = True
    grown.ravel()[second_ends.take(touching)] = True
    grown[:-1] |= chord
    grown[1:] |= chord
    return grown


def _cutting(h_a: np.ndarray, h_b: np.ndarray, tip_height: float) -> np.ndarray:
    """Indices of the segments, with end heights ``h_a`` and ``h_b`` (infinite where not projected), that may cut:
    both ends projected, one below the blank's tip."""
    return np.flatnonzero((np.minimum(h_a, h_b) < tip_height) & (np.maximum(h_a, h_b) < np.inf))


def _lower_envelope(table: PitchTable, tip_height: float, module: float, positions) -> np.ndarray:
    """Blank (heights up to ``tip_height`` over the pitch curve) cut down by the region an outline sweeps through
    ``positions`` (``_positions``, in the gear frame), in the pitch curve's normal coordinates (s, h): the height
    left on each bin of arc length.

    Each bin of arc length keeps the lowest height any bounding segment (an edge at a position, a vertex's
    chord between positions) reaches over it, taken at the segment's ends and where it crosses the bin's
    edges (a segment is straight in (s, h) to second order in its length). Teeth stand along the pitch
    curve's normals, not along the radii, so a tooth leaning on a non-circular gear keeps its flanks.
    """
    perimeter = table.perimeter
    count = int(np.ceil(perimeter / (BIN_MODULES * module)))
    width = perimeter / count
    height, at_edge = np.full(count, tip_height), np.full(count, tip_height)
    radial_arc, tolerance = _radial_arc(table), CONVERGED_MODULES * module
    # polar radius of the blank's tip, a little grown: points beyond it cut nothing; tabulated over one turn of
    # direction from 0, a sample beyond each end
    tip_angle, tip_squared = _polar(table.points + (tip_height + MARGIN_MODULES * module) * table.normals)
    tip_angle = modulo(tip_angle, DIAMOND_TURN)
    order = np.argsort(tip_angle)
    tip_angle = np.r_[tip_angle[order[-1]] - DIAMOND_TURN, tip_angle[order], tip_angle[order[0]] + DIAMOND_TURN]
    tip_squared = tip_squared[np.r_[order[-1], order, order[0]]]
    edges: list[np.ndarray] = []
    chords: list[np.ndarray] = []
    for cloud, first_ends, second_ends in positions:
        angle, squared = _polar(cloud)
        near = squared < np.interp(modulo(angle, DIAMOND_TURN), tip_angle, tip_squared)
        projected = np.flatnonzero(_with_segment_ends(near, first_ends, second_ends))
        # s and h of every placed vertex (flat), h infinite where not projected
        s, h = np.zeros(near.size), np.full(near.size, np.inf)
        s[projected], h[projected] = table.normal_coordinates(cloud.reshape(-1, 2)[projected],
                                                              radial_arc(angle.ravel().take(projected)), tolerance)
        kept = np.flatnonzero(h < tip_height)
        np.minimum.at(height, np.minimum((s.take(kept) / width).astype(int), count - 1), h.take(kept))
        # the segments that may cut (``_cutting``); one with an end never projected (outside the grown tip by the
        # polar test, though made near by another segment of its other end) cuts only at that other end, recorded
        # above
        h_a, h_b = h.take(first_ends), h.take(second_ends)
        cuts = _cutting(h_a, h_b, tip_height)
        first, second = first_ends.take(cuts), second_ends.take(cuts)
        edges.append(np.stack([s.take(first), h_a.take(cuts), s.take(second), h_b.take(cuts)]))
        row = near.shape[1]             # a chord joins a vertex to itself one row on
        cuts = _cutting(h[:-row], h[row:], tip_height)
        chords.append(np.stack([s.take(cuts), h.take(cuts), s.take(cuts + row), h.take(cuts + row)]))
    # the chords against the heights the vertices reach, then the edges against those and the chords' (most
    # edges lie inside the swept region and cut nothing)
    for segments in (chords, edges):
        lowest = np.minimum(height, np.minimum(at_edge, np.roll(at_edge, -1)))      # a bin meets both its edges
        _cut(at_edge, lowest, width, perimeter, np.concatenate(segments, axis=1))
    return np.minimum(height, np.minimum(at_edge, np.roll(at_edge, -1)))


def _envelope(table: PitchTable, tip_height: float, module: float, positions) -> np.ndarray:
    """Outline of the blank cut down by the outline ``positions(share=...)`` sweeps (``_positions``): the lowest
    height of each bin (``_lower_envelope``) over all chunks, or, within ``shared_with``, over one half of the
    chunks here and the other in the twin process, the lower of the two (a bin's height is the least over
    positions). Halves of consecutive chunks, not every other chunk: a segment that cannot lower the bins it
    crosses is passed over (``_cut``), and each half's heights reach low over its own stretch of the curve."""
    twin = _twin.get()
    if twin is None:
        height = _lower_envelope(table, tip_height, module, positions(share=(0, 1)))
    else:
        mine = _lower_envelope(table, tip_height, module, positions(share=(twin.index, 2)))
        height = np.minimum(mine, twin.swap(mine))
    point, _, normal = table.at((np.arange(len(height)) + 0.5) * (table.perimeter / len(height)))
    return point + height[:, None] * normal


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

    return _envelope(table, ADDENDUM * module, module, partial(
        _positions, _short_edges(cutter, table, module), local_facing, reach, _rigid_placement(turn, center)))


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

    # driver points near the line of centres: turned by -phi1 about the driver's centre, then seen from the driven
    # gear (its centre at the center distance, turned by -phi2)
    place = _rigid_placement(-phi1 - phi2, -design.center_distance * np.c_[np.cos(phi2), -np.sin(phi2)])
    # the driver's one-per-bin vertices, thinned where they stay within a hair of their chords
    cutter = _short_edges(thinned(driver_outline, SIMPLIFY_MODULES * module), driven, module)
    return _envelope(driven, ADDENDUM * module, module, partial(_positions, cutter, phi1, reach, place))

"""Where a closed polyline crosses itself, and the same polyline with its small loops cut off at their crossings."""
from __future__ import annotations

import numpy as np
import shapely

from transplanter.geometry.planar import cross


def _side(p, q, r):
    """Sign of the turn p -> q -> r: +1 left, -1 right, 0 collinear."""
    return np.sign((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1])
                   - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))


def crossing_segments(ring: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pairs (i, j), i < j, of segments of a closed polyline (points (N, 2), the last joined to the first; segment
    k from point k to k + 1) that cross properly.

    GEOS (through shapely, in C) decides whether the ring is simple; only a ring that is not is split into
    segments, whose candidate pairs come from an STR-tree of their boxes and are kept where each segment's ends
    lie strictly on both sides of the other. Touches, shared ends and collinear overlaps are not crossings.
    """
    if shapely.is_simple(shapely.linearrings(ring)):
        return np.zeros(0, int), np.zeros(0, int)
    a, b = ring, np.roll(ring, -1, axis=0)
    segments = np.asarray(shapely.linestrings(np.stack([a, b], axis=1)))     # an array of them
    first, second = shapely.STRtree(segments).query(segments)
    i, j = first[first < second], second[first < second]
    crossing = ((_side(a[i], b[i], a[j]) * _side(a[i], b[i], b[j]) < 0)
                & (_side(a[j], b[j], a[i]) * _side(a[j], b[j], b[i]) < 0))
    return i[crossing], j[crossing]


def without_loops(ring: np.ndarray) -> np.ndarray:
    """A closed polyline (N, 2) with each loop it makes by crossing itself cut off at the crossing, the shorter
    way round the ring first (the swallowtail an offset curve makes past a corner or a bend tighter than the
    offset; the crossing point replaces the loop's vertices). A simple ring comes back unchanged."""
    while True:
        first, second = crossing_segments(ring)
        if not len(first):
            return ring
        count = len(ring)
        inside = second - first
        k = int(np.argmin(np.minimum(inside, count - inside)))
        i, j = int(first[k]), int(second[k])
        a, b = ring[i], ring[(i + 1) % count]
        c, d = ring[j], ring[(j + 1) % count]
        along = cross(c - a, d - c) / cross(b - a, d - c)
        crossing = (a + along * (b - a))[None]
        if inside[k] <= count - inside[k]:          # the loop is vertices i + 1 .. j
            ring = np.concatenate([ring[:i + 1], crossing, ring[j + 1:]])
        else:                                       # the loop passes the ring's first vertex: vertices i + 1 .. j stay
            ring = np.concatenate([crossing, ring[i + 1:j + 1]])

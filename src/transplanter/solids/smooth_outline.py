"""A closed outline as a few smooth curves: split at its corners (where consecutive segments turn by more than
``CORNER_DEGREES``), each run between two corners a clamped cubic B-spline (arc-length parameter) fitted by least
squares to every point of the run and refined until each point lies within a given distance of it, its ends on the
run's end points so the curves close.

A run the refinement cannot bring within the distance (a kink below the corner angle) is split at its sharpest
vertex; a run of a few points is interpolated.
"""
from __future__ import annotations

import numpy as np
from scipy.interpolate import BSpline, make_interp_spline, make_lsq_spline

#: A vertex where the outline turns by more than this is a corner: the curves meet there with a kink (a gear's tip
#: corners and the junctions of its cut envelope, a plate's corners).
CORNER_DEGREES = 10.0
DEGREE = 3
#: Knot refinements of a run before it is split at its sharpest vertex instead.
REFINEMENTS = 12


def turns(outline: np.ndarray) -> np.ndarray:
    """The turn (rad, unsigned) at each vertex of a closed outline (N, 2): between the segment in and the one out."""
    along = np.roll(outline, -1, axis=0) - outline
    heading = np.arctan2(along[:, 1], along[:, 0])
    return np.abs((heading - np.roll(heading, 1) + np.pi) % (2 * np.pi) - np.pi)


def smooth_runs(outline: np.ndarray, within: float) -> list[BSpline]:
    """The closed ``outline`` (N, 2) as B-splines of the arc length (2-vectors), in order, each from one corner to
    the next (the first vertex is a corner where there is none), every vertex within ``within`` of its curve."""
    outline = np.asarray(outline, float)
    turn = turns(outline)
    corners = np.flatnonzero(turn > np.radians(CORNER_DEGREES))
    if corners.size == 0:
        corners = np.array([0])
    ends = np.append(corners, corners[0] + len(outline))
    curves: list[BSpline] = []
    for start, end in zip(ends[:-1], ends[1:], strict=True):
        curves += _run_curves(outline, turn, int(start), int(end), within)
    return curves


def _run_curves(outline: np.ndarray, turn: np.ndarray, start: int, end: int, within: float) -> list[BSpline]:
    """The run of vertices ``start``..``end`` (indices taken round the outline) as one curve, or as the curves of
    its two halves split at its sharpest inner vertex where one curve does not come within ``within``."""
    points = outline[np.arange(start, end + 1) % len(outline)]
    curve = _fitted(points, within)
    if curve is not None:
        return [curve]
    middle = start + 1 + int(np.argmax(turn[np.arange(start + 1, end) % len(outline)]))
    return _run_curves(outline, turn, start, middle, within) + _run_curves(outline, turn, middle, end, within)


def _fitted(points: np.ndarray, within: float) -> BSpline | None:
    """A clamped cubic B-spline through the run's end points with every point within ``within``, knots added
    where points are further; a run of too few points for a least-squares fit interpolated; None if
    ``REFINEMENTS`` do not bring it within."""
    length = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
    if len(points) <= 2 * (DEGREE + 1):
        return make_interp_spline(length, points, k=min(DEGREE, len(points) - 1))
    inner = np.empty(0)
    for _ in range(REFINEMENTS):
        knots = np.concatenate([[length[0]] * (DEGREE + 1), inner, [length[-1]] * (DEGREE + 1)])
        try:
            curve = make_lsq_spline(length, points, knots, k=DEGREE)
        except (ValueError, np.linalg.LinAlgError):  # a knot span without a point: no more refinement here
            return None
        curve.c[0], curve.c[-1] = points[0], points[-1]
        off = np.hypot(*(curve(length) - points).T) > within
        if not off.any():
            return curve
        spans = np.concatenate([[length[0]], inner, [length[-1]]])
        bad = np.unique(np.searchsorted(spans, length[off], side="right") - 1).clip(max=len(spans) - 2)
        inner = np.sort(np.concatenate([inner, (spans[bad] + spans[bad + 1]) / 2]))
    return None

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
#: A run's first fit has a knot at every this many points (refined from there).
START_POINTS = 64
#: Knot refinements of a run before it is split at its sharpest vertex instead.
REFINEMENTS = 12
#: Where between two points (fractions of their chord's parameter span) the curve is held near the chord.
BETWEEN = np.array([0.25, 0.5, 0.75])


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
    """A clamped cubic B-spline through the run's end points with every point within ``within`` and, between two
    points, no further from their chord than ``within`` plus twice the chord's sagitta on the circle of the
    neighbouring turns (so sparse points bound the curve too); knots added where it is further. A run of too few
    points for a least-squares fit interpolated; None if ``REFINEMENTS`` do not bring it within."""
    chords = np.diff(points, axis=0)
    chord_length = np.hypot(*chords.T)
    length = np.concatenate([[0.0], np.cumsum(chord_length)])
    between = length[:-1, None] + chord_length[:, None] * BETWEEN  # (chords, 3)
    allowed = within + 2 * _sagitta(points, chord_length)[:, None]
    if len(points) <= 2 * (DEGREE + 1):
        curve = make_interp_spline(length, points, k=min(DEGREE, len(points) - 1))
        return curve if (_chord_distance(curve(between), points, chords) <= allowed).all() else None
    inner = length[START_POINTS:-1:START_POINTS]
    for _ in range(REFINEMENTS):
        knots = np.concatenate([[length[0]] * (DEGREE + 1), inner, [length[-1]] * (DEGREE + 1)])
        try:
            curve = make_lsq_spline(length, points, knots, k=DEGREE)
        except (ValueError, np.linalg.LinAlgError):  # knot spans without points: no more refinement here
            return None
        if not np.isfinite(curve.c).all():  # the same, where the solver does not say so
            return None
        curve.c[0], curve.c[-1] = points[0], points[-1]
        off = np.concatenate([length[np.hypot(*(curve(length) - points).T) > within],
                              between[_chord_distance(curve(between), points, chords) > allowed]])
        if not off.size:
            return curve
        spans = np.concatenate([[length[0]], inner, [length[-1]]])
        bad = np.unique(np.searchsorted(spans, off, side="right") - 1).clip(max=len(spans) - 2)
        inner = np.sort(np.concatenate([inner, (spans[bad] + spans[bad + 1]) / 2]))
    return None


def _sagitta(points: np.ndarray, chord_length: np.ndarray) -> np.ndarray:
    """Per chord of an open run: its sagitta on the circle of the sharper of the turns at its inner ends (the turn
    over the mean of the chords beside it); zero for a run of one chord."""
    if len(points) < 3:
        return np.zeros(len(chord_length))
    heading = np.arctan2(*np.diff(points, axis=0).T[::-1])
    turn = np.abs((np.diff(heading) + np.pi) % (2 * np.pi) - np.pi)
    curvature = np.concatenate([[0.0], turn / ((chord_length[:-1] + chord_length[1:]) / 2), [0.0]])
    return chord_length**2 * np.maximum(curvature[:-1], curvature[1:]) / 8


def _chord_distance(samples: np.ndarray, points: np.ndarray, chords: np.ndarray) -> np.ndarray:
    """Each sample's distance from the chord it lies over: samples (chords, S, 2), row i over points i, i + 1."""
    start, chord = points[:-1, None], chords[:, None]
    along = np.clip(((samples - start) * chord).sum(-1) / (chord * chord).sum(-1), 0, 1)
    return np.hypot(*(samples - start - along[..., None] * chord).transpose(2, 0, 1))

"""Four poses: the center-point and circle-point curves and the dyad family along them.

Both curves are circular cubics (eq 2, ``burmester_center_cubic`` and
``burmester_circle_cubic``). Both pass through the poles P1j, so each is traced completely
by the pencil of lines through the best-conditioned pole (``curve_trace``). Each traced
center gets its circle point from eq (1) and vice versa; both pivots are then polished
together.
"""
from __future__ import annotations

import numpy as np

from transplanter._generated.burmester import burmester_circle_cubic
from transplanter.burmester.five_poses import center_cubic, pencil_pose_order
from transplanter.generated import casadi_function
from transplanter.geometry.curve_trace import CurveTrace, trace_circular_cubic
from transplanter.geometry.pivot_pairing import centers_for_circles, circles_for_centers, polish
from transplanter.geometry.poses import pole


def circle_cubic(poses: np.ndarray) -> np.ndarray:
    cubic = casadi_function(burmester_circle_cubic)
    return np.asarray(cubic(poses[:, 0], poses[:, 1], poses[:, 2])).ravel()


def _pencil_pivot(poses):
    order = pencil_pose_order(poses)
    return pole(poses[0], poses[order[1]])


def trace_center_curve(poses: np.ndarray, directions: int, radius: float) -> CurveTrace:
    return trace_circular_cubic(center_cubic(poses), _pencil_pivot(poses), directions, radius)


def trace_circle_curve(poses: np.ndarray, directions: int, radius: float) -> CurveTrace:
    return trace_circular_cubic(circle_cubic(poses), _pencil_pivot(poses), directions, radius)


def trace_dyads(poses: np.ndarray, directions: int, radius: float, curve: CurveTrace | None = None):
    """Dyads (centers, circles) along the center-point curve, in curve-sample order."""
    curve = curve or trace_center_curve(poses, directions, radius)
    centers = curve.points
    if not len(centers):
        return np.empty((0, 2)), np.empty((0, 2))
    return polish(poses, centers, circles_for_centers(poses, centers))


def dyads_of_circle_curve(poses: np.ndarray, curve: CurveTrace):
    """Dyads (centers, circles) along the circle-point curve, in curve-sample order."""
    circles = curve.points
    if not len(circles):
        return np.empty((0, 2)), np.empty((0, 2))
    return polish(poses, centers_for_circles(poses, circles), circles)

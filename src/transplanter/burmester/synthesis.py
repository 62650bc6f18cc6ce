"""Motion-generation synthesis of RR dyads for any number of poses: one entry point.

The poses are first seen from the dyad's ground (``relative_to_link`` when the ground is
a turning link), then brought to a unit frame for conditioning. The method follows the
pose count: 3 (given pivots), 4 (curves and family), 5 (Burmester points), 6+ (least
squares). Every dyad is checked by ``verify_dyad`` on the original poses before it is returned.
"""
from __future__ import annotations

import numpy as np

from transplanter.api_arguments import require_problem
from transplanter.burmester.five_poses import burmester_points
from transplanter.burmester.four_poses import dyads_of_circle_curve, trace_center_curve, trace_circle_curve, trace_dyads
from transplanter.burmester.many_poses import least_squares_dyads
from transplanter.burmester.problem import DyadProblem
from transplanter.burmester.result import Synthesis
from transplanter.errors import ProblemError
from transplanter.geometry.curve_trace import CurveTrace
from transplanter.geometry.dyad import verify_dyads
from transplanter.geometry.pivot_pairing import centers_for_circles, circles_for_centers
from transplanter.geometry.poses import Frame, pole, relative_to_link

#: Smallest turn between the extreme pose angles that the Burmester construction accepts (rad).
MIN_ROTATION = 1e-6


def working_poses(problem: DyadProblem) -> np.ndarray:
    """The motion the dyad must guide: relative to its ground link when it has one."""
    if problem.link is None:
        return problem.poses
    return relative_to_link(problem.poses, problem.link.pivot, problem.link.phases)


def _check_rotation(poses: np.ndarray, problem: DyadProblem):
    turn = poses[:, 2] - poses[0, 2]
    if np.abs(np.sin(turn / 2)).max() < np.sin(MIN_ROTATION / 2):
        seen = "relative to the turning link " if problem.link is not None else ""
        raise ProblemError(
            f"{problem.source}: poses[].angle_deg: the body does not turn {seen}between the poses "
            f"(pure translation); expected at least two orientations that differ, since a "
            f"translation puts every center point at infinity")


def pure_rotation_center(poses: np.ndarray) -> np.ndarray | None:
    """The point the body turns about when every pose is pose 1 turned about that one point, else None.

    Such poses leave the circle point free: every dyad centred there guides the body. The
    poles of pose 1 with each other pose then coincide, to 1e-9 of the poses' own size (1 mm when they all sit
    on one point), seen in the frame attached to the poses (``Frame``), where rounding does not grow with the
    distance from the origin.
    """
    turned = np.abs(np.sin((poses[1:, 2] - poses[0, 2]) / 2)) >= np.sin(MIN_ROTATION / 2)
    if not turned.all():
        return None
    frame = Frame.of(poses)
    local = frame.local_poses(poses)
    poles = np.array([pole(local[0], other) for other in local[1:]])
    size = max(np.abs(local[:, :2] - local[0, :2]).max(), np.abs(poles - local[0, :2]).max(), 1.0)
    return frame.to_world(poles[0]) if np.abs(poles - poles[0]).max() <= 1e-9 * size else None


def _pure_rotation(problem: DyadProblem, poses: np.ndarray, center: np.ndarray) -> Synthesis:
    """Every dyad centred on ``center`` fits: the given circle points, or one a pose scale off it
    along the body's direction in pose 1 (or ``radius_mm`` / 2 when the poses all sit on one point)."""
    frame = Frame.of(poses)
    radius_mm = problem.radius_mm or 10 * frame.scale
    circles = problem.circle_points
    if not len(circles):
        reach = float(np.linalg.norm(poses[0, :2] - center)) or min(frame.scale, radius_mm / 2)
        circles = center + reach * np.array([[np.cos(poses[0, 2]), np.sin(poses[0, 2])]])
    method = (f"pure rotation about ({center[0]:.6g}, {center[1]:.6g}) mm: every pose is pose 1 turned about "
              "this point, so every dyad centred there guides the body, whatever its circle point "
              "(one shown per given circle point, or one on the body's x axis)")
    centers = np.repeat(center[None, :], len(circles), axis=0)
    return Synthesis(problem, method, verify_dyads(problem.poses, centers, circles, problem.link), radius_mm)


def synthesize(problem: DyadProblem) -> Synthesis:
    """RR dyads that guide the body through the problem's poses, each checked by forward kinematics.

    Parameters
    ----------
    problem : DyadProblem
        Poses in mm and radians (from ``load_problem`` / ``parse_problem`` or built directly).

    Returns
    -------
    Synthesis
        The method used, the dyads (mm), and the Burmester curves for four poses.

    Raises
    ------
    ProblemError
        When the poses do not turn (pure translation).
    """
    require_problem(problem, DyadProblem, "burmester")
    poses = working_poses(problem)
    _check_rotation(poses, problem)
    center = pure_rotation_center(poses)
    if center is not None:
        return _pure_rotation(problem, poses, center + 0.0)     # + 0.0: no -0 in the report
    frame = Frame.of(poses)
    local = frame.local_poses(poses)
    radius_mm = problem.radius_mm or 10 * frame.scale
    radius = radius_mm / frame.scale  # the local frame is centred on the pose centroid
    count = len(poses)

    def to_dyads(centers, circles):
        return verify_dyads(problem.poses, frame.to_world(centers), frame.to_world(circles), problem.link)

    def world_curve(curve: CurveTrace) -> CurveTrace:
        return CurveTrace(frame.to_world(curve.points).reshape(-1, 2), curve.runs)

    if count == 3:
        dyads = []
        if len(problem.circle_points):
            circles = frame.to_local(problem.circle_points)
            dyads += to_dyads(centers_for_circles(local, circles), circles)
        if len(problem.center_points):
            centers = frame.to_local(problem.center_points)
            dyads += to_dyads(centers, circles_for_centers(local, centers))
        return Synthesis(problem, "three poses: the other pivot from eq (1)", dyads, radius_mm)
    if count == 4:
        center_curve = trace_center_curve(local, problem.samples, radius)
        circle_curve = trace_circle_curve(local, problem.samples, radius)
        return Synthesis(problem, "four poses: center-point and circle-point curves (pencil through a pole)",
                         to_dyads(*trace_dyads(local, problem.samples, radius, center_curve)), radius_mm,
                         world_curve(center_curve), world_curve(circle_curve),
                         to_dyads(*dyads_of_circle_curve(local, circle_curve)))
    if count == 5:
        return Synthesis(problem, "five poses: Burmester points (pencil resultant, degree 6)",
                         to_dyads(*burmester_points(local)), radius_mm)
    centers, circles, rms = least_squares_dyads(local, radius)
    return Synthesis(problem, f"{count} poses: least-squares dyads (CasADi/IPOPT)",
                     to_dyads(centers, circles), radius_mm, rms_mm=list(rms * frame.scale))

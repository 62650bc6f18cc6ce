"""Motion-generation synthesis of RR dyads for any number of poses: one entry point.

The poses are first seen from the dyad's ground (``relative_to_link`` when the ground is
a turning link), then brought to a unit frame for conditioning. The method follows the
pose count: 3 (given pivots), 4 (curves and family), 5 (Burmester points), 6+ (least
squares). Every dyad is checked by ``verify_dyad`` on the original poses before it is returned.
"""
from __future__ import annotations

import numpy as np

from transplanter.geometry.curve_trace import CurveTrace
from transplanter.geometry.dyad import verify_dyads
from transplanter.errors import ProblemError
from transplanter.burmester.five_poses import burmester_points
from transplanter.burmester.four_poses import dyads_of_circle_curve, trace_center_curve, trace_circle_curve, trace_dyads
from transplanter.burmester.many_poses import least_squares_dyads
from transplanter.burmester.problem import DyadProblem
from transplanter.burmester.result import Synthesis
from transplanter.geometry.pivot_pairing import centers_for_circles, circles_for_centers
from transplanter.geometry.poses import Frame, relative_to_link

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
    poses = working_poses(problem)
    _check_rotation(poses, problem)
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

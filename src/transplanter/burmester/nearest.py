"""The point of the exact center-point curve nearest a given fixed pivot, and the dyad there.

A sampled curve only bounds the distance from above (by up to half the sample spacing).
The true minimum polishes the nearest sample: minimise |G - p|^2 over the center G and the
circle point M_1 subject to eq (1) for the pose pairs (1, i) (``dyad_constraint``), so that
G stays on the exact curve (a center belongs to it iff some M_1 satisfies eq 1). Given a
link length as well, the constraint |M_1 - G| = length leaves isolated dyads, and the solve
finds the one nearest ``point``. IPOPT solves it in the unit frame of the synthesis.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter._generated.burmester import dyad_constraint
from transplanter.burmester.result import Synthesis
from transplanter.burmester.synthesis import working_poses
from transplanter.errors import ProblemError
from transplanter.generated import casadi_function
from transplanter.geometry.dyad import Dyad, verify_dyad
from transplanter.geometry.poses import Frame
from transplanter.solve import NLPBuilder, Solver

#: Stationarity tolerance: the distance to a point of the exact curve, in the unit frame of the synthesis.
TOLERANCE = 1e-14


@dataclass(frozen=True)
class NearestCenter:
    """The exact dyad whose fixed pivot is nearest ``point`` (mm).

    Attributes
    ----------
    dyad : Dyad
        Center on the exact curve, its circle point and length, checked by forward kinematics.
    distance_mm : float
        True minimum distance from ``point`` to the center-point curve.
    sample_distance_mm : float
        Distance to the nearest traced sample (an upper bound of ``distance_mm`` when no length is
        imposed).
    """

    dyad: Dyad
    distance_mm: float
    sample_distance_mm: float


def _solver(poses: np.ndarray, length: float | None) -> Solver:
    nlp = NLPBuilder()
    center, circle = nlp.variables("center", 2), nlp.variables("circle", 2)
    target = nlp.parameters("target", 2)
    constraint = casadi_function(dyad_constraint).map(len(poses) - 1)
    nlp.constraints("dyad_constraint", constraint(ca.DM(poses[0]), ca.DM(poses[1:].T), center, circle).T, 0.0, 0.0)
    if length is not None:
        nlp.constraints("length", 0.5 * (ca.sumsqr(circle - center) - length**2), 0.0, 0.0)
    return Solver("nearest_center", nlp.build(0.5 * ca.sumsqr(center - target)), tolerance=TOLERANCE)


def nearest_center(result: Synthesis, point, length: float | None = None) -> NearestCenter:
    """The dyad of a four-pose synthesis whose center is nearest ``point`` on the exact curve.

    Parameters
    ----------
    result : Synthesis
        A four-pose synthesis (its traced dyads give the start).
    point : array_like
        The fixed pivot to measure, (x, y) in mm (in pose-1 coordinates of the ground link
        when the problem has one).
    length : float, optional
        Only dyads of this link length (mm): the nearest of the isolated dyads that have it.

    Returns
    -------
    NearestCenter
    """
    problem = result.problem
    if len(problem.poses) != 4 or not result.dyads:
        raise ProblemError(f"{problem.source}: poses: the nearest point of a center-point curve needs four "
                           f"poses and a traced curve, got {len(problem.poses)} poses and {len(result.dyads)} dyads")
    point = np.asarray(point, float)
    poses = working_poses(problem)
    frame = Frame.of(poses)
    gaps = np.array([np.linalg.norm(d.center - point) for d in result.dyads])
    misfit = gaps if length is None else gaps + np.abs([d.length - length for d in result.dyads])
    start = result.dyads[int(np.argmin(misfit))]
    solver = _solver(frame.local_poses(poses), None if length is None else length / frame.scale)
    solution = solver.solve({"center": frame.to_local(start.center), "circle": frame.to_local(start.circle)},
                            parameters={"target": frame.to_local(point)},
                            failure="the nearest point of the center-point curve was not found")
    dyad = verify_dyad(problem.poses, frame.to_world(solution["center"]), frame.to_world(solution["circle"]),
                       problem.link)
    return NearestCenter(dyad, float(np.linalg.norm(dyad.center - point)), float(gaps.min()))

"""Six or more poses: the dyad that best keeps its length, by least squares in CasADi/IPOPT.

Unknowns (local frame): center G, circle point M_1 and length L. Objective: the sum over
poses of (|M_i - G| - L)^2 (``dyad_pivot_distance``). Pivots are bounded to the search
radius. Starts: Burmester points of the first five poses and points of the center-point
curve of the first four, so that every basin the exact solutions suggest is tried.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from transplanter._generated.burmester import dyad_pivot_distance
from transplanter.burmester.five_poses import burmester_points
from transplanter.burmester.four_poses import trace_dyads
from transplanter.errors import SolverError
from transplanter.generated import casadi_function
from transplanter.solve import NLPBuilder, Solver

#: Stationarity tolerance of the least-squares solves: exact poses make the residuals and their gradient
#: vanish, so the solves can go far below the design NLPs' 1e-10.
TOLERANCE = 1e-14


def _solver(poses: np.ndarray, radius: float) -> Solver:
    nlp = NLPBuilder()
    center = nlp.variables("center", 2, -radius, radius)
    circle = nlp.variables("circle", 2, -radius, radius)
    length = nlp.variables("length", 1, 0.0, 4 * radius)
    distances = casadi_function(dyad_pivot_distance).map(len(poses))(ca.DM(poses[0]), ca.DM(poses.T), center, circle)
    return Solver("dyad_least_squares", nlp.build(0.5 * ca.sumsqr(distances.T - length)), tolerance=TOLERANCE)


def _starts(poses: np.ndarray, radius: float, count: int = 16):
    centers, circles = burmester_points(poses[:5])
    starts = list(zip(centers, circles, strict=True))
    family = trace_dyads(poses[:4], directions=4 * count, radius=radius)
    pick = np.linspace(0, len(family[0]) - 1, min(count, len(family[0]))).astype(int)
    starts += [(family[0][k], family[1][k]) for k in pick]
    return starts


def least_squares_dyads(poses: np.ndarray, radius: float, keep: int = 4):
    """Distinct local optima, best first: arrays of centers, circles and RMS length errors."""
    solver = _solver(poses, radius)
    found, statuses = [], []
    for center, circle in _starts(poses, radius):
        try:
            solution = solver.solve({"center": center, "circle": circle, "length": np.linalg.norm(circle - center)})
        except SolverError as error:
            statuses.append(error.status)
            continue
        statuses.append(solution.status)
        found.append((solution.objective, solution.x))
    if not found:
        raise SolverError("least-squares dyad synthesis found no optimum from any start",
                          ", ".join(sorted(set(statuses))) or "no start")
    found.sort(key=lambda item: item[0])
    distinct: list[tuple[float, np.ndarray]] = []
    for value, z in found:
        if all(np.linalg.norm(z[:4] - other[:4]) > 1e-6 for _, other in distinct):
            distinct.append((value, z))
    distinct = distinct[:keep]
    z = np.array([item[1] for item in distinct])
    rms = np.sqrt(2 * np.array([item[0] for item in distinct]) / len(poses))
    return z[:, :2], z[:, 2:4], rms

"""Six or more poses: the dyad that best keeps its length, by least squares in CasADi/IPOPT.

Unknowns (local frame): center G, circle point M_1 and length L. Objective: the sum over
poses of (|M_i - G| - L)^2 (``dyad_pivot_distance``). Pivots are bounded to the search
radius. Starts: Burmester points of the first five poses and points of the center-point
curve of the first four, so that every basin the exact solutions suggest is tried.
"""
from __future__ import annotations

import casadi as ca
import numpy as np

from transplanter.burmester.five_poses import burmester_points
from transplanter.burmester.four_poses import trace_dyads
from transplanter.errors import SolverError
from transplanter.generated import casadi_function

_ACCEPTED = {"Solve_Succeeded", "Solved_To_Acceptable_Level"}


def _solver(poses: np.ndarray):
    z = ca.SX.sym("z", 5)  # center (2), circle (2), length
    distance = casadi_function("burmester", "dyad_pivot_distance")
    distances = distance.map(len(poses))(ca.DM(poses[0]), ca.DM(poses.T), z[:2], z[2:4])
    residual = distances.T - z[4]
    nlp = {"x": z, "f": 0.5 * ca.sumsqr(residual)}
    options = {"print_time": False, "ipopt": {"print_level": 0, "sb": "yes", "tol": 1e-14}}
    return ca.nlpsol("dyad_least_squares", "ipopt", nlp, options)


def _starts(poses: np.ndarray, radius: float, count: int = 16):
    centers, circles = burmester_points(poses[:5])
    starts = list(zip(centers, circles))
    family = trace_dyads(poses[:4], directions=4 * count, radius=radius)
    pick = np.linspace(0, len(family[0]) - 1, min(count, len(family[0]))).astype(int) if len(family[0]) else []
    starts += [(family[0][k], family[1][k]) for k in pick]
    return starts


def least_squares_dyads(poses: np.ndarray, radius: float, keep: int = 4):
    """Distinct local optima, best first: arrays of centers, circles and RMS length errors."""
    solver = _solver(poses)
    bound = [radius] * 4 + [4 * radius]
    found, statuses = [], []
    for center, circle in _starts(poses, radius):
        length = np.linalg.norm(circle - center)
        result = solver(x0=[*center, *circle, length], lbx=[-b for b in bound[:4]] + [0.0], ubx=bound)
        status = solver.stats()["return_status"]
        statuses.append(status)
        if status in _ACCEPTED:
            z = np.asarray(result["x"]).ravel()
            found.append((float(result["f"]), z))
    if not found:
        raise SolverError("least-squares dyad synthesis found no optimum from any start",
                          ", ".join(sorted(set(statuses))) or "no start")
    found.sort(key=lambda item: item[0])
    distinct = []
    for value, z in found:
        if all(np.linalg.norm(z[:4] - other[:4]) > 1e-6 for _, other in distinct):
            distinct.append((value, z))
    distinct = distinct[:keep]
    z = np.array([item[1] for item in distinct])
    rms = np.sqrt(2 * np.array([item[0] for item in distinct]) / len(poses))
    return z[:, :2], z[:, 2:4], rms

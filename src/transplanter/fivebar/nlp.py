"""Precise design of the five-bar and its relative angle as one NLP (CasADi/IPOPT).

Unknowns (lengths in units of ``SCALE`` mm inside the NLP): carrier length L1 and its
angle at pose 1, rod length L2, hinge B, receiving plate L4, E and F in the plate frame,
rho1 and the spline's control values (q_0 = 0), and for each return point j its carrier
turn c_j, the plate direction there and the point P_j' the mechanism actually reaches.

Constraints:
- key poses (equalities): with the plate exactly in pose i, |E_i - B| = L4 and
  F_i = A(c_i) + L2 e(theta1(c_i) + rho(c_i)): the chain closes there with P and the plate
  angle exactly as asked;
- return points (equalities): the same closure for the plate at (P_j', direction_j);
- whole turn, on ``GRID_POINTS`` carrier turns plus any added ones: the derived closure
  margin ``fivebar_closure_margin`` (sin^2 of angle EBF, eq 10 scale-free) at least the
  margin, and 1/i_max <= rho' <= 1/i_min (rho strictly increasing: the gears never reverse);
- the B-E-F assembly of the start at all nine positions; c_j increasing between the last
  key pose and a full turn; the ``[ranges]`` limits.

Between grid points the margin and rho' may dip: ``refine_design`` checks both on a grid
``CHECK_POINTS`` fine by independent forward kinematics and re-solves with the worst
carrier turns added to the grid (an exchange method), until the fine grid holds.

Objective: sum_j |P_j' - P_j|^2 / SCALE^2 (return points in least squares) plus
``BENDING_WEIGHT`` times the bending int rho''^2 dc, which picks the smoothest relative
angle (hence the gentlest gears) among designs that fit equally well.
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter.errors import SolverError
from transplanter.fivebar.candidate import Candidate
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.generated import casadi_function
from transplanter.geometry.periodic_bspline import CASADI, TWO_PI, basis, basis_matrix
from transplanter.fivebar.relative_angle import RelativeAngle, bending_matrix
from transplanter.fivebar.return_stroke import ReturnStroke

SCALE = 100.0
GRID_POINTS = 180
CHECK_POINTS = 7200
EXCHANGE_ROUNDS = 4
BENDING_WEIGHT = 1e-6
MIN_STEP = np.radians(1.0)   # smallest carrier turn between consecutive positions


@dataclass(frozen=True)
class DesignSolution:
    mech: FiveBar
    relative_angle: RelativeAngle
    stroke: ReturnStroke
    reached_return_points: np.ndarray   # P_j' (mm)
    objective: float
    iterations: int
    status: str


def _unit(angle):
    return ca.vertcat(ca.cos(angle), ca.sin(angle))


def _rot(angle, v):
    c, s = ca.cos(angle), ca.sin(angle)
    return ca.vertcat(c * v[0] - s * v[1], s * v[0] + c * v[1])


def _cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


@dataclass(frozen=True)
class DesignNLP:
    """The NLP in casadi form: decision vector, objective, constraints with bounds, start."""

    x: ca.SX
    objective: ca.SX
    constraints: ca.SX
    lbg: np.ndarray
    ubg: np.ndarray
    lbx: np.ndarray
    x0: np.ndarray
    branch: float


def build_nlp(problem: FiveBarProblem, start: Candidate, added_turns=()) -> DesignNLP:
    n, m = problem.spline_count, len(problem.return_points)
    poses = problem.poses.copy()
    poses[:, :2] /= SCALE
    targets = problem.return_points / SCALE
    turns = problem.carrier_turns

    x = ca.SX.sym("x", 11 + (n - 1) + 4 * m)
    l1, theta11, l2, bx, by, l4, ex, ey, fx, fy, rho1 = (x[k] for k in range(11))
    q = ca.vertcat(0, x[11:10 + n])
    ret = ca.reshape(x[10 + n:], 4, m)
    b, e_loc, f_loc = ca.vertcat(bx, by), ca.vertcat(ex, ey), ca.vertcat(fx, fy)
    q0 = basis_matrix(np.zeros(1), n)[0]

    def rho(c):
        return rho1 + c + ca.dot(ca.vertcat(*basis(c, n, 0, CASADI)), q) - ca.dot(ca.DM(q0), q)

    equalities, inequalities = [], []
    branch = start.mech.branch
    positions = [(poses[i, :2], poses[i, 2], turns[i], rho1 + ca.dot(ca.DM(basis_matrix(turns[i:i + 1], n)[0] - q0), q)
                  + turns[i]) for i in range(4)]
    positions += [(ret[2:4, j], ret[1, j], ret[0, j], rho(ret[0, j])) for j in range(m)]
    for p, direction, c, angle in positions:
        e = p + _rot(direction, e_loc)
        f = p + _rot(direction, f_loc)
        theta1 = theta11 - c
        a = l1 * _unit(theta1)
        equalities += [ca.sumsqr(e - b) - l4**2, f - a - l2 * _unit(theta1 + angle)]
        inequalities.append(branch * _cross(f - b, e - b) / (l4 * ca.norm_2(f - b)))

    grid = np.r_[np.linspace(0, TWO_PI, GRID_POINTS, endpoint=False), added_turns]
    points = len(grid)
    rho_grid = rho1 + grid + ca.mtimes(ca.DM(basis_matrix(grid, n) - q0), q)
    slope = 1 + ca.mtimes(ca.DM(basis_matrix(grid, n, 1)), q)
    theta1_grid = theta11 - grid
    lengths = ca.vertcat(l1, l2, ca.norm_2(e_loc - f_loc), l4, ca.norm_2(b))
    crank = ca.horzcat(theta1_grid, theta1_grid + rho_grid, ca.repmat(ca.atan2(by, -bx), points, 1)).T
    margin = casadi_function("fivebar", "fivebar_closure_margin").map(points)(ca.repmat(lengths, 1, points), crank)

    e1 = poses[0, :2] + _rot(poses[0, 2], e_loc)
    f1 = poses[0, :2] + _rot(poses[0, 2], f_loc)
    ranged = {"ep": ca.norm_2(e_loc) * SCALE, "fp": ca.norm_2(f_loc) * SCALE, "x_e": e1[0] * SCALE, "x_f": f1[0] * SCALE}
    order = ca.vertcat(ret[0, 0] - turns[-1], ca.diff(ret[0, :].T), TWO_PI - ret[0, m - 1])

    g = ca.vertcat(*equalities, *inequalities, margin.T, slope, order, *(ranged[k] for k in problem.ranges))
    low_ratio, high_ratio = problem.ratio_bounds
    sqrt_margin = np.sqrt(problem.min_closure_margin)
    lbg = np.r_[np.zeros(3 * (4 + m)), np.full(4 + m, sqrt_margin), np.full(points, problem.min_closure_margin),
                np.full(points, 1 / high_ratio), np.full(m + 1, MIN_STEP),
                [problem.ranges[k][0] for k in problem.ranges]]
    ubg = np.r_[np.zeros(3 * (4 + m)), np.full(4 + m, np.inf), np.full(points, np.inf),
                np.full(points, 1 / low_ratio), np.full(m + 1, np.inf),
                [problem.ranges[k][1] for k in problem.ranges]]
    objective = ca.sumsqr(ret[2:4, :] - targets.T) + BENDING_WEIGHT * ca.mtimes([q.T, ca.DM(bending_matrix(n)), q])

    lbx = np.r_[1e-3, -np.inf, 1e-3, -np.inf, -np.inf, 1e-3, np.full(5 + (n - 1) + 4 * m, -np.inf)]
    return DesignNLP(x, objective, g, lbg, ubg, lbx, _start_vector(start, problem), branch)


def design_nlp(problem: FiveBarProblem, start: Candidate, added_turns=()) -> DesignSolution:
    nlp = build_nlp(problem, start, added_turns)
    solver = ca.nlpsol("fivebar_design", "ipopt", {"x": nlp.x, "f": nlp.objective, "g": nlp.constraints},
                       {"ipopt.print_level": 0, "ipopt.sb": "yes", "print_time": False, "ipopt.tol": 1e-12,
                        "ipopt.constr_viol_tol": 1e-12, "ipopt.max_iter": 1000})
    solution = solver(x0=nlp.x0, lbg=nlp.lbg, ubg=nlp.ubg, lbx=nlp.lbx, ubx=np.full(len(nlp.lbx), np.inf))
    stats = solver.stats()
    if not stats["success"]:
        raise SolverError(f"{problem.source}: the design NLP did not converge from the region candidate",
                          stats["return_status"])
    return _unpack(np.asarray(solution["x"]).ravel(), problem, nlp.branch, float(solution["f"]), stats)


def refine_design(problem: FiveBarProblem, start: Candidate) -> DesignSolution:
    """``design_nlp``, with the carrier turns where a fine check finds the margin or rho' out of
    bounds added to its grid, until the fine grid holds (or ``EXCHANGE_ROUNDS`` run out)."""
    fine = np.linspace(0, TWO_PI, CHECK_POINTS, endpoint=False)
    low, high = 1 / problem.ratio_bounds[1], 1 / problem.ratio_bounds[0]
    added = np.empty(0)
    for _ in range(EXCHANGE_ROUNDS):
        solution = design_nlp(problem, start, added)
        margin = solution.mech.forward(fine, solution.relative_angle.evaluate(fine))["margin"]
        slope = solution.relative_angle.evaluate(fine, 1)
        shortfall = np.fmax(problem.min_closure_margin - margin, np.fmax(low - slope, slope - high))
        worst = fine[_local_maxima(shortfall)]
        if not worst.size:
            break
        added = np.r_[added, worst]
    return solution


def _local_maxima(shortfall: np.ndarray) -> np.ndarray:
    """Indices of the periodic local maxima of a shortfall where it is positive beyond rounding."""
    peak = (shortfall >= np.roll(shortfall, 1)) & (shortfall > np.roll(shortfall, -1))
    return np.flatnonzero(peak & (shortfall > 1e-9))


def _start_vector(start: Candidate, problem: FiveBarProblem) -> np.ndarray:
    mech, relative, stroke = start.mech, start.relative_angle, start.stroke
    head = [mech.carrier_length / SCALE, mech.carrier_angle, mech.rod_length / SCALE, *(mech.hinge_b / SCALE),
            mech.receiving_length / SCALE, *(mech.e_local / SCALE), *(mech.f_local / SCALE), relative.rho1]
    tail = np.stack([stroke.carrier_turns, stroke.directions, *(problem.return_points.T / SCALE)]).T.ravel()
    return np.r_[head, relative.coefficients[1:], tail]


def _unpack(v: np.ndarray, problem: FiveBarProblem, branch: float, objective: float, stats) -> DesignSolution:
    n, m = problem.spline_count, len(problem.return_points)
    mech = FiveBar(carrier_length=v[0] * SCALE, carrier_angle=float(v[1]), rod_length=v[2] * SCALE,
                   hinge_b=v[3:5] * SCALE, receiving_length=v[5] * SCALE, e_local=v[6:8] * SCALE,
                   f_local=v[8:10] * SCALE, branch=branch)
    relative = RelativeAngle(float(v[10]), np.r_[0.0, v[11:10 + n]])
    ret = v[10 + n:].reshape(m, 4)
    rho = relative.evaluate(ret[:, 0])
    stroke = ReturnStroke(ret[:, 0], rho, ret[:, 1])
    return DesignSolution(mech, relative, stroke, ret[:, 2:4] * SCALE, objective, int(stats["iter_count"]),
                          stats["return_status"])

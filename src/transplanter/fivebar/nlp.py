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

Between grid points the margin and rho' may dip: ``DesignSolver.refine`` checks both on a
grid ``CHECK_POINTS`` fine by independent forward kinematics and re-solves, from the last
design, with the worst carrier turns added to the grid (an exchange method), until the fine
grid holds. The added turns, the start's assembly branch and the start itself are inputs of
the call, not of the NLP's expressions, so one IPOPT solver serves every start and round.

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
#: Exchange points one solver holds before it is rebuilt larger.
ADDED_CAPACITY = 16
#: The objective is ~1e-6 at the optimum, so its multipliers are tiny and IPOPT's stopping test
#: would accept slacks ~1e-7 on active constraints; scaled by 1e3 it pins them ~100x closer, and
#: the adaptive barrier update then takes ~25 iterations per candidate instead of ~90.
IPOPT_OPTIONS = {"ipopt.print_level": 0, "ipopt.sb": "yes", "print_time": False, "ipopt.tol": 1e-12,
                 "ipopt.constr_viol_tol": 1e-12, "ipopt.max_iter": 1000, "ipopt.obj_scaling_factor": 1e3,
                 "ipopt.mu_strategy": "adaptive"}


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
    """The NLP in casadi form, for any start and up to ``capacity`` exchange points.

    The parameters ``p`` are the start's assembly branch (+1 or -1) and, per exchange slot,
    its carrier turn, spline basis row and basis-derivative row (``parameters``). A slot
    left empty gets unbounded rows (``bounds``), so it constrains nothing.
    """

    x: ca.SX
    p: ca.SX
    objective: ca.SX
    constraints: ca.SX
    lbg: np.ndarray            # every slot active
    ubg: np.ndarray
    lbx: np.ndarray
    slot_rows: np.ndarray      # (2, capacity): the margin row and the rho' row of each slot
    spline_count: int

    @property
    def capacity(self) -> int:
        return self.slot_rows.shape[1]

    def bounds(self, added: int) -> tuple[np.ndarray, np.ndarray]:
        """lbg, ubg with the first ``added`` exchange slots active and the others free."""
        lbg, ubg = self.lbg.copy(), self.ubg.copy()
        free = self.slot_rows[:, added:].ravel()
        lbg[free], ubg[free] = -np.inf, np.inf
        return lbg, ubg

    def parameters(self, branch: float, added_turns: np.ndarray) -> np.ndarray:
        """Value of ``p`` for a start's branch and the exchange points' carrier turns (rad)."""
        turns = np.r_[added_turns, np.zeros(self.capacity - len(added_turns))]
        n = self.spline_count
        return np.r_[branch, turns, basis_matrix(turns, n).ravel(), basis_matrix(turns, n, 1).ravel()]


def build_nlp(problem: FiveBarProblem, capacity: int = ADDED_CAPACITY) -> DesignNLP:
    """The design NLP of ``problem`` with room for ``capacity`` exchange points."""
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

    branch = ca.SX.sym("branch")
    added_turns = ca.SX.sym("added_turns", capacity)
    added_basis = ca.SX.sym("added_basis", n, capacity)
    added_slope_basis = ca.SX.sym("added_slope_basis", n, capacity)

    def rho(c):
        return rho1 + c + ca.dot(ca.vertcat(*basis(c, n, 0, CASADI)), q) - ca.dot(ca.DM(q0), q)

    equalities, inequalities = [], []
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

    fixed = np.linspace(0, TWO_PI, GRID_POINTS, endpoint=False)
    grid = ca.vertcat(ca.DM(fixed), added_turns)
    points = GRID_POINTS + capacity
    rho_grid = rho1 + grid + ca.mtimes(ca.vertcat(ca.DM(basis_matrix(fixed, n)), added_basis.T), q) - ca.dot(ca.DM(q0), q)
    slope = 1 + ca.mtimes(ca.vertcat(ca.DM(basis_matrix(fixed, n, 1)), added_slope_basis.T), q)
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
    first_margin_row = 4 * (4 + m) + GRID_POINTS
    slot_rows = first_margin_row + np.arange(capacity) + np.array([[0], [points]])
    objective = ca.sumsqr(ret[2:4, :] - targets.T) + BENDING_WEIGHT * ca.mtimes([q.T, ca.DM(bending_matrix(n)), q])

    lbx = np.r_[1e-3, -np.inf, 1e-3, -np.inf, -np.inf, 1e-3, np.full(5 + (n - 1) + 4 * m, -np.inf)]
    p = ca.vertcat(branch, added_turns, ca.vec(added_basis), ca.vec(added_slope_basis))
    return DesignNLP(x, p, objective, g, lbg, ubg, lbx, slot_rows, n)


class DesignSolver:
    """The design NLP of one problem as one IPOPT solver, reused for every start and exchange round.

    ``builds`` counts how often the solver was built: once, unless the exchange needs more
    than ``ADDED_CAPACITY`` points (it is then rebuilt with twice the room).
    """

    def __init__(self, problem: FiveBarProblem):
        self.problem = problem
        self.builds = 0
        self._build(ADDED_CAPACITY)

    def _build(self, capacity: int):
        self.nlp = build_nlp(self.problem, capacity)
        self.function = ca.nlpsol("fivebar_design", "ipopt",
                                  {"x": self.nlp.x, "p": self.nlp.p, "f": self.nlp.objective, "g": self.nlp.constraints},
                                  IPOPT_OPTIONS)
        self.builds += 1

    def solve(self, start: Candidate, added_turns=(), warm: DesignSolution | None = None) -> DesignSolution:
        """Solve with the start's assembly branch and the exchange points ``added_turns`` (rad),
        from the start's own dimensions or from the design ``warm`` (a previous round's)."""
        added_turns = np.asarray(added_turns, float)
        while len(added_turns) > self.nlp.capacity:
            self._build(2 * self.nlp.capacity)
        nlp, branch = self.nlp, start.mech.branch
        lbg, ubg = nlp.bounds(len(added_turns))
        if warm is None:
            x0 = decision_vector(start.mech, start.relative_angle, start.stroke, self.problem.return_points)
        else:
            x0 = decision_vector(warm.mech, warm.relative_angle, warm.stroke, warm.reached_return_points)
        solution = self.function(x0=x0, p=nlp.parameters(branch, added_turns), lbg=lbg, ubg=ubg, lbx=nlp.lbx,
                                 ubx=np.full(len(nlp.lbx), np.inf))
        stats = self.function.stats()
        if not stats["success"]:
            raise SolverError(f"{self.problem.source}: the design NLP did not converge from the region candidate",
                              stats["return_status"])
        return _unpack(np.asarray(solution["x"]).ravel(), self.problem, branch, float(solution["f"]), stats)

    def refine(self, start: Candidate) -> DesignSolution:
        """``solve``, with the carrier turns where a fine check finds the margin or rho' out of
        bounds added to its grid, until the fine grid holds (or ``EXCHANGE_ROUNDS`` run out)."""
        problem = self.problem
        fine = np.linspace(0, TWO_PI, CHECK_POINTS, endpoint=False)
        low, high = 1 / problem.ratio_bounds[1], 1 / problem.ratio_bounds[0]
        added, solution = np.empty(0), None
        for _ in range(EXCHANGE_ROUNDS):
            solution = self.solve(start, added, solution)
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


def decision_vector(mech: FiveBar, relative: RelativeAngle, stroke: ReturnStroke,
                    return_points: np.ndarray) -> np.ndarray:
    """The decision vector of a design whose return points stand at ``return_points`` (mm)."""
    head = [mech.carrier_length / SCALE, mech.carrier_angle, mech.rod_length / SCALE, *(mech.hinge_b / SCALE),
            mech.receiving_length / SCALE, *(mech.e_local / SCALE), *(mech.f_local / SCALE), relative.rho1]
    tail = np.stack([stroke.carrier_turns, stroke.directions, *(return_points.T / SCALE)]).T.ravel()
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

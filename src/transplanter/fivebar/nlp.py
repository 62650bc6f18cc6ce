"""Precise design of the five-bar and its relative angle as one NLP (CasADi/IPOPT) that maximises
the smallest transmission quality over the whole turn.

Unknowns (lengths in units of ``length_unit(problem)`` inside the NLP): carrier length L1 and its angle at
pose 1, rod length L2, hinge B, receiving plate L4, E and F in the plate frame, rho1 and the
spline's control values (q_0 = 0), for each return point j its carrier turn c_j, the plate
direction there and the point P_j' the mechanism actually reaches; then the transmission
quality t and the train's correction k (eq 12).

Transmission quality. F is driven (the carrier and the gears place it); the dyad F-E-B then
places the plate. Two angles of the triangle B-E-F measure how well it does:
- angle EBF, whose sin^2 is the derived closure margin ``fivebar_closure_margin`` (eq 10
  without its scale): where it vanishes the circles about B and F touch and the chain jams;
- angle BEF, the dyad's transmission angle proper: the rocker BE is a two-force link, so the
  force it takes is the load's moment about F over L3 sin(BEF), and E moves by at most
  1 / sin(BEF) times F's displacement.
By the sine rule sin(BEF) = |BF| sin(EBF) / L3: both vanish together, but they differ by the
factor |BF| / L3 that changes round the turn. Both count: t <= sin^2(EBF) and
t <= sin^2(BEF) = margin |BF|^2 / L3^2 on the grid, and the NLP maximises t. (Where
|BF| >= L3 all round, e.g. L4 >= 2 L3 as on the bundled example, angle EBF is the smaller one
and the rows of BEF stay inactive.) ``min_closure_margin`` stays a hard floor: t >= it.

Constraints:
- key poses (equalities): with the plate exactly in pose i, |E_i - B| = L4 and
  F_i = A(c_i) + L2 e(theta1(c_i) + rho(c_i)): the chain closes there with P and the plate
  angle exactly as asked;
- return points: the same closure for the plate at (P_j', direction_j), and
  |P_j' - P_j|^2 <= return_tolerance_mm^2 (a tolerance 0 fixes P_j' = P_j);
- whole turn, on ``GRID_POINTS`` carrier turns, the left sides of the spline's knots (rho's third
  derivative jumps there, and a kappa with it; the basis takes the right side) and any added turns:
  the two quality rows,
  1/i_max <= rho' <= 1/i_min (rho strictly increasing: the gears never reverse), and the four
  pitch curves' curvature times the stage's center distance (``train_pitch_curvature``,
  derived) held by a kappa >= u for sun, both intermediates and planet, u fixed by its bounds;
- k int_0^2pi sqrt(rho') dc = 2 pi, the integral by ``QUADRATURE_NODES``-point Gauss-Legendre
  on each knot span (rho' is a quadratic there, so sqrt(rho') is smooth on the span; with 12
  nodes the row agrees with ``trains.planetary.correction_factor`` to ~1e-13, with 6 only to ~1e-7);
- the B-E-F assembly of the start at all nine positions; c_j increasing between the last
  key pose and a full turn; the ``[ranges]`` limits.

Concavity. A rack cannot cut a hollow; a shaper can, when its pitch circle (radius m N / 2) fits
the hollow, whose radius is a / |a kappa|. ``refine`` therefore holds u = -``CONCAVITY_LIMIT``
(a hollow no tighter than a / 6: a 16-tooth shaper fits once a > 48 m); ``make_convex`` then tries
u = ``CURVATURE_FLOOR`` (convex, rack-cut) from that design with at most ``CONVEX_ATTEMPT_ITERATIONS``
per solve, and keeps it only when IPOPT succeeds (the alternatives try it once per mechanism, not
once per start). The rows are switched by their bounds and u's
(no rebuild); ``curvature_floor`` and ``convexity_note`` say which held.

Between grid points the quality, rho' and the curvatures may dip: ``DesignSolver.refine``
checks them on a grid ``CHECK_POINTS`` fine, by independent forward kinematics
(``FiveBar.forward``) and the library's quadrature of k, and re-solves, from the last design,
with the worst carrier turns added to the grid (an exchange method), until the fine grid holds
(the quality to ``QUALITY_GAP`` of t). The added turns, the start's assembly branch and the
start itself are inputs of the call, not of the NLP's expressions, so one IPOPT solver serves
every start and round. The turns an exchange added are offered to every later start from its
first solve (``exchange_turns``): each row holds a condition the whole turn must meet anyway, so
they change no solution, and starts that end in the same mechanism need one round, not three.

Objective: -t plus ``BENDING_WEIGHT`` times the bending int S''^2 dc of the spline. Without it
the spline is free wherever no constraint is active and the max-min has no unique solution;
with it, the smoothest relative angle (the gentlest gears) among the nearly equally good ones.
The weight costs t at most ``BENDING_WEIGHT`` times the bending of the pure max-min design (the
regulariser's value there): on the bundled example 4e-5 in sin^2 (0.2 %, 0.01 deg of angle EBF),
for half the bending (int S''^2 = 22 instead of 40); 1e-4 would cost 1.5 %.
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter.errors import SolverError
from transplanter.fivebar.candidate import Candidate
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, bending_matrix
from transplanter.fivebar.return_stroke import ReturnStroke
from transplanter.generated import casadi_function, numpy_twin
from transplanter.geometry.periodic_bspline import CASADI, TWO_PI, basis, basis_matrix, knots
from transplanter.geometry.turn_quadrature import NODES, panels
from transplanter.trains.planetary import correction_factor

GRID_POINTS = 72
CHECK_POINTS = 7200
EXCHANGE_ROUNDS = 4
BENDING_WEIGHT = 1e-5
QUADRATURE_NODES = NODES   # Gauss-Legendre nodes per knot span for k (12: the rule is exact to ~1e-13)
#: Smallest a kappa allowed on a pitch curve (a: the stage's center distance). A circle of radius
#: a / 2 has 2; the floor keeps each curve strictly convex, its curvature radius below 50 a.
CURVATURE_FLOOR = 0.02
#: The fine check adds carrier turns where the quality falls below t by more than this fraction.
QUALITY_GAP = 1e-3
#: ... or where a kappa falls below the value it is held at by more than this fraction of that value's size.
CURVATURE_GAP = 1e-3
#: A row is on its bound when within this fraction of the bound's size (IPOPT stops at 1e-12), or when
#: its multiplier exceeds MULTIPLIER_FLOOR (the objective's gradient in t is 1; IPOPT leaves ~1e-10 on
#: rows far from their bounds).
ROW_ON_BOUND_TOLERANCE = 1e-6
MULTIPLIER_FLOOR = 1e-6
#: The NLP's grid holds the curvature rows just left of each knot, this far (rad): the curvature is smooth
#: on a span, so this is its left limit to ~1e-9 relative.
KNOT_SIDE = 1e-9
MIN_STEP = np.radians(1.0)   # smallest carrier turn between consecutive positions
#: Exchange points one solver holds before it is rebuilt larger.
ADDED_CAPACITY = 16
#: Largest |a kappa| of a concave stretch (a: the stage's center distance): a hollow no tighter than
#: a / 6, which a shaper of N teeth and module m fits once a > 6 m N / 2 (48 m for N = 16). The
#: undercut-free counts of the whole-tooth train already make a that large on the bundled example.
CONCAVITY_LIMIT = 6.0
#: Iterations each solve of the attempt at convex curves may take, from the design held at
#: -CONCAVITY_LIMIT (a design solve takes 20-50).
CONVEX_ATTEMPT_ITERATIONS = 25
#: A solve that keeps a row off its bounds by more than STALL_VIOLATION of the row's size for
#: STALL_ITERATIONS iterations in a row has stalled and is stopped. Solves that succeed on the bundled
#: example take 17-63 iterations in all; its one start that fails crawls for 850 iterations with rows
#: off by several percent (steps cut 8-9 times by the line search), about 10 s of the job.
STALL_VIOLATION, STALL_ITERATIONS = 1e-3, 100
#: Carrier turns on which ``other_passes`` looks for the passes of P by the return points (0.1 deg apart).
PASS_POINTS = 3600
CURVES = ("sun", "first intermediate", "second intermediate", "planet")
#: The rows each exchange slot holds, in order (``DesignNLP.slot_rows``).
SLOT_ROWS = ("angle EBF", "angle BEF", "ratio", *(f"curvature {curve}" for curve in CURVES))
#: No parameter multipliers (calc_lam_p off) lets casadi skip building the NLP's gradient function (no_nlp_grad):
#: the build takes 0.01-0.07 s less of 0.52-0.62 s (five fresh processes each), and the solves are identical.
IPOPT_OPTIONS = {"ipopt.print_level": 0, "ipopt.sb": "yes", "print_time": False, "ipopt.tol": 1e-10,
                 "ipopt.constr_viol_tol": 1e-12, "ipopt.max_iter": 1000, "ipopt.mu_strategy": "adaptive",
                 "calc_lam_p": False, "no_nlp_grad": True}

_curvature = numpy_twin("train_pitch_curvature", "train_pitch_curvature")


@dataclass(frozen=True)
class DesignSolution:
    """A refined design and its whole-turn figures, the latter from an independent fine-grid evaluation
    (``FiveBar.forward``; the derived curvature with the library's k), never the NLP's own variables.

    Attributes
    ----------
    mech, relative_angle, stroke
        The five-bar (mm, rad), rho(c) and the return stroke.
    reached_return_points : ndarray, shape (m, 2)
        P_j' of the NLP (mm); ``return_misses_mm`` are |P - P_j| by forward kinematics at c_j.
    objective, iterations, status
        IPOPT's final objective (-t + bending term), iterations and return status.
    quality : float
        t, the NLP's smallest min(sin^2 EBF, sin^2 BEF) on its grid.
    min_closure_margin, min_closure_turn : float
        Smallest sin^2(angle EBF) over ``CHECK_POINTS`` carrier turns, and the turn (rad) where it is.
    min_angle_ebf, min_angle_bef, min_angle_bef_turn : float
        Smallest angles EBF and BEF (rad) and where BEF's is (rad).
    correction : float
        k of eq (12) by the library's quadrature.
    min_curvature : tuple of 4 float
        Smallest a kappa of sun, first intermediate, second intermediate, planet (``CURVES``).
    curvature_floor : float or None
        The least a kappa the curvature rows held: ``CURVATURE_FLOOR`` (convex), -``CONCAVITY_LIMIT``
        (shaper-cut hollows), None (rows off); ``convexity_note`` says why, with the numbers, when not convex.
    active_bounds : tuple of str
        Every bound the solution sits on (within ``ROW_ON_BOUND_TOLERANCE`` of its size).
    """

    mech: FiveBar
    relative_angle: RelativeAngle
    stroke: ReturnStroke
    reached_return_points: np.ndarray   # P_j' (mm)
    objective: float
    iterations: int
    status: str
    quality: float
    return_misses_mm: np.ndarray
    min_closure_margin: float
    min_closure_turn: float
    min_angle_ebf: float
    min_angle_bef: float
    min_angle_bef_turn: float
    correction: float
    min_curvature: tuple
    active_bounds: tuple
    curvature_floor: float | None = None
    convexity_note: str = ""


class _IterationCap(ca.Callback):
    """IPOPT's iteration callback: stops the solve after ``limit`` iterations (None: never), or when it
    has stalled: ``STALL_ITERATIONS`` iterations in a row with a row off its bounds by more than
    ``STALL_VIOLATION`` of the row's size (``stalled`` then says so). ``watch`` arms it for a solve."""

    def __init__(self, variables: int, rows: int):
        ca.Callback.__init__(self)
        self.variables, self.rows = variables, rows
        self.limit, self.count, self.stalled = None, 0, False
        self.lbg = self.ubg = self.scales = None
        self.infeasible_run = 0
        self.construct("iteration_cap", {})

    def watch(self, limit: int | None, lbg: np.ndarray, ubg: np.ndarray, scales: np.ndarray):
        self.limit, self.lbg, self.ubg, self.scales = limit, lbg, ubg, scales
        self.count, self.infeasible_run, self.stalled = 0, 0, False

    def get_n_in(self):
        return ca.nlpsol_n_out()

    def get_n_out(self):
        return 1

    def get_name_in(self, i):
        return ca.nlpsol_out(i)

    def get_name_out(self, i):
        return "stop"

    def get_sparsity_in(self, i):
        name = ca.nlpsol_out(i)
        if name == "f":
            return ca.Sparsity.scalar()
        if name in ("x", "lam_x"):
            return ca.Sparsity.dense(self.variables)
        if name in ("g", "lam_g"):
            return ca.Sparsity.dense(self.rows)
        return ca.Sparsity(0, 0)

    def eval(self, arg):
        self.count += 1
        violation = relative_violation(np.asarray(arg[ca.nlpsol_out().index("g")]).ravel(), self.lbg, self.ubg,
                                       self.scales)
        self.infeasible_run = self.infeasible_run + 1 if not violation <= STALL_VIOLATION else 0
        self.stalled = self.infeasible_run >= STALL_ITERATIONS
        return [int(self.stalled or (self.limit is not None and self.count > self.limit))]


def relative_violation(g: np.ndarray, lbg: np.ndarray, ubg: np.ndarray, scales: np.ndarray) -> float:
    """The largest amount by which a row lies outside its bounds, as a fraction of the row's size (0:
    every row holds; NaN rows count as infinitely far)."""
    with np.errstate(invalid="ignore"):
        outside = np.fmax(lbg - g, g - ubg) / scales
    return float(np.max(np.where(np.isnan(g), np.inf, np.fmax(outside, 0.0)), initial=0.0))


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
    its carrier turn and spline basis rows of orders 0-3 (``parameters``). A slot left empty
    gets unbounded rows (``bounds``), so it constrains nothing; so do the convexity rows when
    switched off.
    """

    x: ca.SX
    p: ca.SX
    objective: ca.SX
    constraints: ca.SX
    lbg: np.ndarray            # every slot active, convexity rows on
    ubg: np.ndarray
    lbx: np.ndarray
    ubx: np.ndarray
    slot_rows: np.ndarray      # (len(SLOT_ROWS), capacity)
    curvature_rows: np.ndarray  # every convexity row, grid and slots
    bound_names: list          # per row: (name of its lower bound, of its upper bound) or None
    bound_scales: np.ndarray   # per row: the size an active row is judged against
    spline_count: int
    exact_return_points: bool  # return_tolerance_mm = 0: P_j' held at P_j by its bounds
    unit: float                # mm per NLP length unit (``length_unit``)

    @property
    def capacity(self) -> int:
        return self.slot_rows.shape[1]

    def bounds(self, added: int, convex: bool = False) -> tuple[np.ndarray, np.ndarray]:
        """lbg, ubg with the first ``added`` exchange slots active and the others free, and the
        convexity rows (a kappa >= u) on or off."""
        lbg, ubg = self.lbg.copy(), self.ubg.copy()
        free = np.r_[self.slot_rows[:, added:].ravel(), [] if convex else self.curvature_rows].astype(int)
        lbg[free], ubg[free] = -np.inf, np.inf
        return lbg, ubg

    def parameters(self, branch: float, added_turns: np.ndarray) -> np.ndarray:
        """Value of ``p`` for a start's branch and the exchange points' carrier turns (rad)."""
        turns = np.r_[added_turns, np.zeros(self.capacity - len(added_turns))]
        n = self.spline_count
        return np.r_[branch, turns, *(basis_matrix(turns, n, order).ravel() for order in range(4))]

    def variable_bounds(self, x0: np.ndarray, curvature_floor: float | None) -> tuple[np.ndarray, np.ndarray]:
        """lbx, ubx with the least a kappa u held at ``curvature_floor`` (the rows say a kappa >= it), or,
        where the rows are off (None), at its start value."""
        lbx, ubx = self.lbx.copy(), self.ubx.copy()
        lbx[-1] = ubx[-1] = x0[-1] if curvature_floor is None else curvature_floor
        return lbx, ubx


def reach(problem: FiveBarProblem) -> float:
    """The problem's own size (mm): the largest distance of a key pose or return point from O."""
    return float(np.hypot(*np.vstack([problem.poses[:, :2], problem.return_points]).T).max())


def length_unit(problem: FiveBarProblem) -> float:
    """The NLP's unit of length (mm): the power of ten at or below the reach (100 mm on the bundled
    example). Lengths of order one keep IPOPT's tolerances and the bounds on lengths (1e-3 of the unit)
    relative to the problem, and a problem scaled by a power of ten is the same NLP."""
    return float(10.0 ** np.floor(np.log10(reach(problem))))


def build_nlp(problem: FiveBarProblem, capacity: int = ADDED_CAPACITY) -> DesignNLP:
    """The design NLP of ``problem`` with room for ``capacity`` exchange points."""
    n, m = problem.spline_count, len(problem.return_points)
    poses = problem.poses.copy()
    unit = length_unit(problem)
    poses[:, :2] /= unit
    targets = problem.return_points / unit
    turns = problem.carrier_turns

    x = ca.SX.sym("x", 14 + (n - 1) + 4 * m)
    l1, theta11, l2, bx, by, l4, ex, ey, fx, fy, rho1 = (x[k] for k in range(11))
    q = ca.vertcat(0, x[11:10 + n])
    ret = ca.reshape(x[10 + n:10 + n + 4 * m], 4, m)
    quality, correction, least_curvature = x[-3], x[-2], x[-1]
    b, e_loc, f_loc = ca.vertcat(bx, by), ca.vertcat(ex, ey), ca.vertcat(fx, fy)
    q0 = basis_matrix(np.zeros(1), n)[0]

    branch = ca.SX.sym("branch")
    added_turns = ca.SX.sym("added_turns", capacity)
    added_basis = [ca.SX.sym(f"added_basis_{order}", n, capacity) for order in range(4)]

    def rho(c):
        return rho1 + c + ca.dot(ca.vertcat(*basis(c, n, 0, CASADI)), q) - ca.dot(ca.DM(q0), q)

    equalities, assembly = [], []
    positions = [(poses[i, :2], poses[i, 2], turns[i], rho1 + ca.dot(ca.DM(basis_matrix(turns[i:i + 1], n)[0] - q0), q)
                  + turns[i]) for i in range(4)]
    positions += [(ret[2:4, j], ret[1, j], ret[0, j], rho(ret[0, j])) for j in range(m)]
    for p, direction, c, angle in positions:
        e = p + _rot(direction, e_loc)
        f = p + _rot(direction, f_loc)
        theta1 = theta11 - c
        a = l1 * _unit(theta1)
        equalities += [ca.sumsqr(e - b) - l4**2, f - a - l2 * _unit(theta1 + angle)]
        assembly.append(branch * _cross(f - b, e - b) / (l4 * ca.norm_2(f - b)))

    fixed = np.r_[np.linspace(0, TWO_PI, GRID_POINTS, endpoint=False), _knot_left_sides(n)]
    grid = ca.vertcat(ca.DM(fixed), added_turns)
    points = len(fixed) + capacity
    rows = [ca.vertcat(ca.DM(basis_matrix(fixed, n, order)), added_basis[order].T) for order in range(4)]
    rho_grid = rho1 + grid + ca.mtimes(rows[0], q) - ca.dot(ca.DM(q0), q)
    slope = 1 + ca.mtimes(rows[1], q)
    theta1_grid = theta11 - grid
    l3_squared = ca.sumsqr(e_loc - f_loc)
    lengths = ca.vertcat(l1, l2, ca.sqrt(l3_squared), l4, ca.norm_2(b))
    crank = ca.horzcat(theta1_grid, theta1_grid + rho_grid, ca.repmat(ca.atan2(by, -bx), points, 1)).T
    margin = casadi_function("fivebar", "fivebar_closure_margin").map(points)(ca.repmat(lengths, 1, points), crank).T
    f_grid = ca.horzcat(l1 * ca.cos(theta1_grid) + l2 * ca.cos(crank[1, :].T) - bx,
                        l1 * ca.sin(theta1_grid) + l2 * ca.sin(crank[1, :].T) - by)
    transmission = margin * ca.sum2(f_grid**2) / l3_squared          # sin^2(BEF) = margin |BF|^2 / L3^2
    derivatives = ca.horzcat(slope, ca.mtimes(rows[2], q), ca.mtimes(rows[3], q)).T
    curvature = casadi_function("train_pitch_curvature", "train_pitch_curvature").map(points)(
        derivatives, ca.repmat(correction, 1, points))[1]
    spans = panels(knots(n), count=n, nodes=QUADRATURE_NODES)
    root_slope = ca.sqrt(1 + ca.mtimes(ca.DM(basis_matrix(spans.nodes.ravel(), n, 1)), q))
    closure_k = correction * ca.dot(ca.DM(spans.weights.ravel()), root_slope) - TWO_PI

    e1 = poses[0, :2] + _rot(poses[0, 2], e_loc)
    f1 = poses[0, :2] + _rot(poses[0, 2], f_loc)
    ranged = {"ep": ca.norm_2(e_loc), "fp": ca.norm_2(f_loc), "x_e": e1[0], "x_f": f1[0]}
    order = ca.vertcat(ret[0, 0] - turns[-1], ca.diff(ret[0, :].T), TWO_PI - ret[0, m - 1])
    misses = ca.sum1((ret[2:4, :] - targets.T) ** 2).T
    tolerance = (problem.return_tolerance_mm / unit) ** 2

    low_ratio, high_ratio = problem.ratio_bounds
    sqrt_margin = np.sqrt(problem.min_closure_margin)
    labels = [*problem.labels, *problem.return_labels]
    blocks = [  # (expression, lower, upper, (lower name, upper name) per row or one for all, scale)
        (ca.vertcat(*equalities), 0.0, 0.0, None, 1.0),
        (ca.vertcat(*assembly), sqrt_margin, np.inf, [(f"assembly at {k}", None) for k in labels], sqrt_margin),
        (margin - quality, 0.0, np.inf, None, 1.0),
        (transmission - quality, 0.0, np.inf, None, 1.0),
        (slope, 1 / high_ratio, 1 / low_ratio, ("ratio upper", "ratio lower"), 1 / high_ratio),
        *((curvature[k, :].T - least_curvature, 0.0, np.inf, (f"curvature {curve}", None), CURVATURE_FLOOR)
          for k, curve in enumerate(CURVES)),
        (closure_k, 0.0, 0.0, None, 1.0),
        (order, MIN_STEP, np.inf, ("return order", None), MIN_STEP),
        *((ranged[key], low / unit, high / unit, (f"ranges.{key} lower", f"ranges.{key} upper"),
           max(abs(low), abs(high)) / unit) for key, (low, high) in problem.ranges.items()),
        (misses, -np.inf, tolerance if tolerance > 0 else np.inf,
         [(None, f"return point {k} tolerance") for k in problem.return_labels], tolerance),
    ]
    g, lbg, ubg, names, scales, starts = [], [], [], [], [], []
    for expression, low, high, name, scale in blocks:
        size = expression.shape[0]
        starts.append(sum(len(v) for v in lbg))
        g.append(expression)
        lbg.append(np.full(size, low, float))
        ubg.append(np.full(size, high, float))
        names += name if isinstance(name, list) else [name or (None, None)] * size
        scales.append(np.full(size, scale, float))
    slot_rows = np.array([starts[k] + len(fixed) + np.arange(capacity) for k in range(2, 9)])
    curvature_rows = np.concatenate([starts[k] + np.arange(points) for k in range(5, 9)])

    bending = ca.mtimes([q.T, ca.DM(bending_matrix(n)), q])
    lbx = np.r_[1e-3, -np.inf, 1e-3, -np.inf, -np.inf, 1e-3, np.full(5 + (n - 1) + 4 * m, -np.inf),
                problem.min_closure_margin, 0.0, -CONCAVITY_LIMIT]
    ubx = np.r_[np.full(len(lbx) - 1, np.inf), -CONCAVITY_LIMIT]
    if tolerance == 0:
        fixed_points = 10 + n + 4 * np.arange(m)[:, None] + np.array([2, 3])
        lbx[fixed_points], ubx[fixed_points] = targets, targets
    p = ca.vertcat(branch, added_turns, *(ca.vec(v) for v in added_basis))
    objective = -quality + BENDING_WEIGHT * bending
    return DesignNLP(x, p, objective, ca.vertcat(*g), np.concatenate(lbg),
                     np.concatenate(ubg), lbx, ubx, slot_rows, curvature_rows, names, np.concatenate(scales), n,
                     tolerance == 0, unit)


class DesignSolver:
    """The design NLP of one problem as one IPOPT solver, reused for every start and exchange round.

    ``builds`` counts how often the solver was built: once, unless the exchange needs more
    than ``ADDED_CAPACITY`` points (it is then rebuilt with twice the room).
    """

    def __init__(self, problem: FiveBarProblem):
        self.problem = problem
        self.builds = 0
        self.exchange_turns = np.empty(0)     # turns earlier exchanges added (rad), offered to later starts
        self._build(ADDED_CAPACITY)

    def _build(self, capacity: int):
        self.nlp = build_nlp(self.problem, capacity)
        self.cap = _IterationCap(self.nlp.x.shape[0], self.nlp.constraints.shape[0])
        self.function = ca.nlpsol("fivebar_design", "ipopt",
                                  {"x": self.nlp.x, "p": self.nlp.p, "f": self.nlp.objective, "g": self.nlp.constraints},
                                  {**IPOPT_OPTIONS, "iteration_callback": self.cap})
        self.builds += 1

    def solve(self, start: Candidate, added_turns=(), warm: DesignSolution | None = None,
              curvature_floor: float | None = None, iteration_limit: int | None = None) -> DesignSolution:
        """Solve with the start's assembly branch and the exchange points ``added_turns`` (rad),
        from the start's own dimensions or from the design ``warm`` (a previous round's), with the
        four curves held to a kappa >= ``curvature_floor`` (None: the rows off); ``iteration_limit``
        stops IPOPT early (a ``SolverError``)."""
        added_turns = np.asarray(added_turns, float)
        while len(added_turns) > self.nlp.capacity:
            self._build(2 * self.nlp.capacity)
        nlp, branch = self.nlp, start.mech.branch
        if warm is None:
            x0 = decision_vector(start.mech, start.relative_angle, start.stroke, self.problem.return_points, nlp.unit)
        else:
            x0 = decision_vector(warm.mech, warm.relative_angle, warm.stroke, warm.reached_return_points, nlp.unit)
        lbg, ubg = nlp.bounds(len(added_turns), curvature_floor is not None)
        lbx, ubx = nlp.variable_bounds(x0, curvature_floor)
        self.cap.watch(iteration_limit, lbg, ubg, nlp.bound_scales)
        solution = self.function(x0=x0, p=nlp.parameters(branch, added_turns), lbg=lbg, ubg=ubg, lbx=lbx, ubx=ubx)
        stats = self.function.stats()
        if not stats["success"]:
            status = (f"a stall (a row off its bounds by more than {STALL_VIOLATION:g} of its size for "
                      f"{STALL_ITERATIONS} iterations in a row, after {self.cap.count})"
                      if self.cap.stalled else stats["return_status"])
            raise SolverError(f"{self.problem.source}: the design NLP did not converge from the region candidate",
                              status)
        active = _active_bounds(nlp, solution, lbg, ubg)
        return _unpack(np.asarray(solution["x"]).ravel(), self.problem, nlp.unit, branch, float(solution["f"]), stats,
                       active, curvature_floor)

    def refine(self, start: Candidate) -> DesignSolution:
        """The best transmission quality from ``start`` with every pitch curve a shaper can cut:
        a kappa >= -``CONCAVITY_LIMIT`` (``_exchange``). If IPOPT fails there, a ``HollowError`` gives
        the least a kappa of the design made without the rows (a hollow that only gears many times the
        mechanism's size could carry: 2700 teeth at module 1.5 on one start of the bundled example)."""
        try:
            return self._exchange(start, -CONCAVITY_LIMIT)
        except SolverError as error:
            unheld = _curvature_text(self._exchange(start, None))
            raise HollowError(f"IPOPT ended with {error.status} with the pitch curves held to a kappa >= "
                              f"{-CONCAVITY_LIMIT:g} (hollows a shaper cuts); without that hold: {unheld}",
                              error.status) from None

    def make_convex(self, start: Candidate, design: DesignSolution) -> DesignSolution:
        """``design`` (``refine``'s from ``start``) with convex pitch curves (rack-cut), when IPOPT gets
        there from it within ``CONVEX_ATTEMPT_ITERATIONS`` per solve; else ``design`` itself, its
        ``convexity_note`` saying why and what the curves are."""
        if design.curvature_floor is None or min(design.min_curvature) >= CURVATURE_FLOOR:
            return design
        try:
            return self._exchange(start, CURVATURE_FLOOR, warm=design, iteration_limit=CONVEX_ATTEMPT_ITERATIONS)
        except SolverError as error:
            failure = f"IPOPT found no convex design within {CONVEX_ATTEMPT_ITERATIONS} iterations ({error.status})"
        return dataclasses.replace(design, convexity_note=f"{failure}; {concavity_text(design)}")

    def restroke(self, start: Candidate, design: DesignSolution, point: int, turn: float) -> DesignSolution:
        """``refine`` from ``design`` with return point ``point`` passed at carrier turn ``turn`` (rad, another
        pass of P by it: ``other_passes``) instead of its own: the NLP keeps each return point on the pass it
        starts on, so a design whose P passes a return point twice has a second stroke to try."""
        turns = design.stroke.carrier_turns.copy()
        turns[point] = turn
        rho = design.relative_angle.evaluate(turns)
        state = design.mech.forward(turns, rho)
        directions, reached = design.stroke.directions.copy(), design.reached_return_points.copy()
        directions[point], reached[point] = state["direction"][point], state["p"][point]
        warm = dataclasses.replace(design, stroke=ReturnStroke(turns, rho, directions), reached_return_points=reached)
        return self._exchange(start, -CONCAVITY_LIMIT, warm=warm)

    def _exchange(self, start: Candidate, curvature_floor: float | None, warm: DesignSolution | None = None,
                  iteration_limit: int | None = None) -> DesignSolution:
        """``solve`` with the carrier turns where the fine check finds the quality below t, or rho' or a
        curvature (below ``curvature_floor``) out of bounds, added to its grid, until the fine grid holds
        (or ``EXCHANGE_ROUNDS`` run out)."""
        problem = self.problem
        fine = np.linspace(0, TWO_PI, CHECK_POINTS, endpoint=False)
        low, high = 1 / problem.ratio_bounds[1], 1 / problem.ratio_bounds[0]
        added, solution = self.exchange_turns, warm
        for _ in range(EXCHANGE_ROUNDS):
            solution = self.solve(start, added, solution, curvature_floor, iteration_limit)
            check = whole_turn(solution.mech, solution.relative_angle, fine)
            slope = check["slope"]
            shortfall = np.fmax.reduce([
                (solution.quality - np.fmin(check["ebf"], check["bef"])) / solution.quality - QUALITY_GAP,
                (problem.min_closure_margin - check["ebf"]) / problem.min_closure_margin,
                (low - slope) / low, (slope - high) / high,
                *([] if curvature_floor is None else
                  (curvature_floor - check["curvature"]) / abs(curvature_floor) - CURVATURE_GAP)])
            worst = fine[_local_maxima(shortfall)]
            if not worst.size:
                break
            added = np.r_[added, worst]
        self.exchange_turns = added[-(self.nlp.capacity // 2):]     # room left for a new start's own rounds
        return solution


class HollowError(SolverError):
    """A start whose pitch curves cannot be held to hollows a shaper cuts; ``reason`` says with what numbers."""

    def __init__(self, reason: str, status: str):
        super().__init__(reason, status)
        self.reason = reason


def other_passes(problem: FiveBarProblem, design: DesignSolution) -> list[tuple[int, float]]:
    """(return point index, carrier turn in rad) of every other pass of P by a return point that the
    stroke's order allows: each local minimum of |P(c) - P_j| over ``PASS_POINTS`` carrier turns between
    the neighbours' turns (``MIN_STEP`` clear of them; the last key pose and a full turn at the ends),
    except the one nearest the design's own turn c_j."""
    turns = np.linspace(0, TWO_PI, PASS_POINTS, endpoint=False)
    p = design.mech.forward(turns, design.relative_angle.evaluate(turns))["p"]
    own, found = design.stroke.carrier_turns, []
    bounds = np.r_[problem.carrier_turns[-1], own, TWO_PI]
    for j, point in enumerate(problem.return_points):
        distance = np.linalg.norm(p - point, axis=1)
        minima = np.flatnonzero((distance <= np.roll(distance, 1)) & (distance < np.roll(distance, -1)))
        minima = minima[(turns[minima] > bounds[j] + MIN_STEP) & (turns[minima] < bounds[j + 2] - MIN_STEP)]
        if minima.size:
            nearest = minima[np.argmin(np.abs(turns[minima] - own[j]))]
            found += [(j, float(turns[k])) for k in minima if k != nearest]
    return found


def _knot_left_sides(count: int) -> np.ndarray:
    """Carrier turns just left of the spline's ``count`` knots, where a kappa takes its left limit."""
    return np.mod(knots(count) - KNOT_SIDE, TWO_PI)


def _curvature_text(design: DesignSolution) -> str:
    return "least a kappa " + ", ".join(f"{curve} {value:.3f}" for curve, value in zip(CURVES, design.min_curvature))


def concavity_text(design: DesignSolution) -> str:
    """The held design's least a kappa per curve, the tightest, and the cutter that follows."""
    tightest = int(np.argmin(design.min_curvature))
    stages = sorted({("sun -> first intermediate", "second intermediate -> planet")[k // 2]
                     for k, value in enumerate(design.min_curvature) if value < 0})
    return (f"held to a kappa >= {-CONCAVITY_LIMIT:g} (a hollow no tighter than a / {CONCAVITY_LIMIT:g}): "
            f"{_curvature_text(design)}, tightest the {CURVES[tightest]}; concave, so shaper-cut: "
            + ", ".join(stages))


def whole_turn(mech: FiveBar, relative: RelativeAngle, turns: np.ndarray) -> dict:
    """sin^2 of the angles EBF and BEF (forward kinematics), rho', and a kappa of the four pitch curves
    (rows of ``CURVES``, with k by the train's own quadrature) at carrier turns ``turns``."""
    state = mech.forward(turns, relative.evaluate(turns))
    distance = np.linalg.norm(state["f"] - mech.hinge_b, axis=-1)
    slope = [relative.evaluate(turns, order) for order in (1, 2, 3)]
    k = correction_factor(relative)
    curvature = _curvature(slope, [np.full_like(turns, k)])[1]
    return {"ebf": state["margin"], "bef": state["margin"] * distance**2 / mech.link_length**2, "slope": slope[0],
            "curvature": curvature, "correction": k, "p": state["p"]}


def _active_bounds(nlp: DesignNLP, solution: dict, lbg: np.ndarray, ubg: np.ndarray) -> tuple:
    """Names of the bounds the solution sits on, each once, in row order: a bound counts when the row is
    within ``ROW_ON_BOUND_TOLERANCE`` of its size from it, or when IPOPT's multiplier on it exceeds
    ``MULTIPLIER_FLOOR`` (an interior point stops a hair inside a bound that still binds)."""
    v, g = np.asarray(solution["x"]).ravel(), np.asarray(solution["g"]).ravel()
    lam_g, lam_x = np.asarray(solution["lam_g"]).ravel(), np.asarray(solution["lam_x"]).ravel()
    names = []
    if v[-3] - nlp.lbx[-3] <= ROW_ON_BOUND_TOLERANCE * nlp.lbx[-3] or lam_x[-3] < -MULTIPLIER_FLOOR:
        names.append("closure margin floor")
    for (lower, upper), value, low, high, scale, lam in zip(nlp.bound_names, g, lbg, ubg, nlp.bound_scales, lam_g):
        if lower and np.isfinite(low) and (value - low <= ROW_ON_BOUND_TOLERANCE * scale or lam < -MULTIPLIER_FLOOR):
            names.append(lower)
        if upper and np.isfinite(high) and (high - value <= ROW_ON_BOUND_TOLERANCE * scale or lam > MULTIPLIER_FLOOR):
            names.append(upper)
    if nlp.exact_return_points:
        names += [name for (_, name) in nlp.bound_names if name and name.startswith("return point")]
    return tuple(dict.fromkeys(names))


def _local_maxima(shortfall: np.ndarray) -> np.ndarray:
    """Indices of the periodic local maxima of a shortfall where it is positive beyond rounding."""
    peak = (shortfall >= np.roll(shortfall, 1)) & (shortfall > np.roll(shortfall, -1))
    return np.flatnonzero(peak & (shortfall > 1e-9))


def decision_vector(mech: FiveBar, relative: RelativeAngle, stroke: ReturnStroke,
                    return_points: np.ndarray, unit: float) -> np.ndarray:
    """The decision vector of a design whose return points stand at ``return_points`` (mm), lengths in
    ``unit`` mm; t, k and u start at the design's own quality, correction factor and least a kappa on
    the NLP's grid."""
    head = [mech.carrier_length / unit, mech.carrier_angle, mech.rod_length / unit, *(mech.hinge_b / unit),
            mech.receiving_length / unit, *(mech.e_local / unit), *(mech.f_local / unit), relative.rho1]
    tail = np.stack([stroke.carrier_turns, stroke.directions, *(return_points.T / unit)]).T.ravel()
    check = whole_turn(mech, relative, np.linspace(0, TWO_PI, GRID_POINTS, endpoint=False))
    return np.r_[head, relative.coefficients[1:], tail, np.nanmin(np.fmin(check["ebf"], check["bef"])),
                 check["correction"], np.nanmin(check["curvature"])]


def _unpack(v: np.ndarray, problem: FiveBarProblem, unit: float, branch: float, objective: float, stats,
            active: tuple, curvature_floor: float | None) -> DesignSolution:
    n, m = problem.spline_count, len(problem.return_points)
    mech = FiveBar(carrier_length=v[0] * unit, carrier_angle=float(v[1]), rod_length=v[2] * unit,
                   hinge_b=v[3:5] * unit, receiving_length=v[5] * unit, e_local=v[6:8] * unit,
                   f_local=v[8:10] * unit, branch=branch)
    relative = RelativeAngle(float(v[10]), np.r_[0.0, v[11:10 + n]])
    ret = v[10 + n:10 + n + 4 * m].reshape(m, 4)
    rho = relative.evaluate(ret[:, 0])
    stroke = ReturnStroke(ret[:, 0], rho, ret[:, 1])
    fine = np.linspace(0, TWO_PI, CHECK_POINTS, endpoint=False)
    check = whole_turn(mech, relative, fine)
    reached = mech.forward(stroke.carrier_turns, rho)["p"]
    ebf, bef = int(np.argmin(check["ebf"])), int(np.argmin(check["bef"]))
    return DesignSolution(
        mech, relative, stroke, ret[:, 2:4] * unit, objective, int(stats["iter_count"]), stats["return_status"],
        quality=float(v[-3]), return_misses_mm=np.linalg.norm(reached - problem.return_points, axis=1),
        min_closure_margin=float(check["ebf"][ebf]), min_closure_turn=float(fine[ebf]),
        min_angle_ebf=float(np.arcsin(np.sqrt(check["ebf"][ebf]))),
        min_angle_bef=float(np.arcsin(np.sqrt(min(check["bef"][bef], 1.0)))), min_angle_bef_turn=float(fine[bef]),
        correction=check["correction"], min_curvature=tuple(float(v) for v in np.fmin(
            check["curvature"].min(axis=1), whole_turn(mech, relative, _knot_left_sides(n))["curvature"].min(axis=1))),
        active_bounds=active, curvature_floor=curvature_floor,
        convexity_note="" if curvature_floor is not None else "curvature rows off")

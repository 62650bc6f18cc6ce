"""The design NLP of the five-bar and its relative angle (``solve`` layer, IPOPT): maximise the smallest
transmission angle at E over the whole turn.

Variables (lengths in units of ``length_unit(problem)`` inside the NLP), each a named block: carrier length
L1 and its angle at pose 1, rod length L2, hinge B, receiving plate L4, E and F in the plate frame, rho1
and the spline's control values (q_0 = 0), the return stroke (per return point j its carrier turn c_j,
the plate direction there and the point P_j' the mechanism actually reaches), the transmission quality t,
the train's correction k (eq 12), the least a kappa u the curvature rows hold, and each banded key-pose
quantity, named as the file names it (``key_poses.P2.angle_deg``) and held within its band.

Transmission quality. F is driven (the carrier and the gears place it); the plate E-F-P is held at E by the
receiving plate BE, a two-force link, so a load at P is balanced about F by the force in BE, which is the
load's moment about F over L3 sin(mu), mu the angle between EF and BE at E: the transmission angle that
carries the load. t <= sin^2(mu) on the grid and the NLP maximises t; ``conditions.min_transmission_angle_deg``
is a floor on t. Angle EBF, whose sin^2 is the closure margin (eq 10 without its scale: where it vanishes the
chain jams), is held above ``min_closure_margin``. Both are the derived triangle margins
(``fivebar_triangle_margins``: law of cosines in |BF|^2), equal to eq (10)'s form and a fraction of its
operations in the Hessian.

Constraints, each a named block (every closure equation from ``derivations/fivebar.py``):
- ``pose_closure``: at the key poses (as chosen within their bands) and the return points (the plate at
  (P_j', direction_j)) the loop closes at position level: |E - B| = L4 and F = A + L2 e(theta1 + rho);
- ``assembly``: the start's B-E-F assembly branch at every position, with the closure margin there;
- on the grid (``GRID_POINTS`` carrier turns, the left sides of the spline's knots, where a kappa jumps,
  and ``capacity`` exchange slots whose turns are parameters): ``closure_margin`` (>= its floor),
  ``transmission_quality`` (sin^2 mu >= t), ``slope`` (1/i_max <= rho' <= 1/i_min: the gears never
  reverse), ``curvature_<curve>`` (a kappa >= u for the four pitch curves, ``train_pitch_curvature``) and
  ``pressure_angle_stage_<j>`` (the teeth's pressure angle alpha0 + |mu| within ``[gears]
  max_pressure_angle_deg``, mu the lean of the pitch curves' common tangent, ``trains.pressure_angle``);
- ``correction_closure``: k int_0^2pi sqrt(rho') dc = 2 pi by ``QUADRATURE_NODES``-point Gauss-Legendre
  per knot span (rho' is a quadratic there: the row agrees with ``trains.planetary.correction_factor``
  to about 1e-13);
- ``return_order``: c_j increasing between the last key pose and a full turn; ``ranges.<name>``: the
  ``[ranges]`` limits; ``return_misses``: |P_j' - P_j| within ``return_tolerance_mm`` (0 fixes P_j');
  ``key_order``: banded carrier turns in order; ``requirements.<name>``: the relative requirements between
  the chosen key poses (``fivebar.key_pose_bands``).

Concavity. A rack cannot cut a hollow; a shaper can, when its pitch circle (radius m N / 2) fits the
hollow, whose radius is a / |a kappa|. The solver holds u = -``CONCAVITY_LIMIT`` first, then tries
``CURVATURE_FLOOR`` (convex); the rows are switched by their bounds, not by rebuilding.

Objective: -t plus ``BENDING_WEIGHT`` times the bending int S''^2 dc of the spline: without it the
spline is free wherever no constraint binds and the max-min has no unique optimum; with it, the
smoothest relative angle among the nearly equally good ones, for a cost in t of at most the weight
times the pure max-min design's bending.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from transplanter._generated.fivebar import (
    fivebar_assembly_sine,
    fivebar_plate_hinges,
    fivebar_pose_closure,
    fivebar_triangle_margins,
)
from transplanter._generated.train_pitch_curvature import train_pitch_curvature
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, bending_matrix
from transplanter.fivebar.return_stroke import ReturnStroke
from transplanter.fivebar.whole_turn import CURVES, knot_left_sides, whole_turn
from transplanter.generated import casadi_function
from transplanter.geometry.periodic_bspline import CASADI, TWO_PI, basis, basis_matrix, knots
from transplanter.geometry.turn_quadrature import NODES, panels
from transplanter.solve import ActiveBound, Bounds, NLPBuilder, NLPLayout, Solution
from transplanter.solve.multipliers import Multipliers
from transplanter.trains.pressure_angle import pressure_rows

GRID_POINTS = 72
BENDING_WEIGHT = 1e-5
QUADRATURE_NODES = NODES   # Gauss-Legendre nodes per knot span for k (12: the rule is exact to ~1e-13)
#: Smallest a kappa allowed on a pitch curve (a: the stage's center distance). A circle of radius
#: a / 2 has 2; the floor keeps each curve strictly convex, its curvature radius below 50 a.
CURVATURE_FLOOR = 0.02
#: Largest |a kappa| of a concave stretch (a: the stage's center distance): a hollow no tighter than
#: a / 6, which a shaper of N teeth and module m fits once a > 6 m N / 2 (48 m for N = 16).
CONCAVITY_LIMIT = 6.0
MIN_STEP = np.radians(1.0)   # smallest carrier turn between consecutive positions
#: Exchange slots one NLP holds before it is rebuilt larger.
ADDED_CAPACITY = 16
#: The grid blocks each exchange slot adds a row to.
CURVATURE_BLOCKS = tuple(f"curvature_{c.replace(' ', '_')}" for c in CURVES)
PRESSURE_BLOCKS = ("pressure_angle_stage_1", "pressure_angle_stage_2")
GRID_BLOCKS = ("closure_margin", "transmission_quality", "closure_quality", "slope", *CURVATURE_BLOCKS,
               *PRESSURE_BLOCKS)
#: Report name of the gear pressure angle's bound.
PRESSURE_LIMIT = "gears.max_pressure_angle_deg"
#: Report names of the return tolerance and of the curvature hold (``active_bounds`` groups by them).
RETURN_TOLERANCE = "conditions.return_tolerance_mm"


@dataclass(frozen=True)
class DesignSolution:
    """A refined design and its whole-turn figures, the latter from an independent fine-grid evaluation
    (``whole_turn``: ``FiveBar.forward``, the derived curvature with the library's k), never the NLP's own
    variables.

    Attributes
    ----------
    mech, relative_angle, stroke
        The five-bar (mm, rad), rho(c) and the return stroke.
    reached_return_points : ndarray, shape (m, 2)
        P_j' of the NLP (mm); ``return_misses_mm`` are |P - P_j| by forward kinematics at c_j.
    objective, iterations, status
        IPOPT's final objective (-t + bending term), iterations and return status.
    quality : float
        t, the NLP's smallest sin^2 of the transmission angle at E (angle BEF) on its grid.
    min_closure_margin, min_closure_turn : float
        Smallest sin^2(angle EBF) over ``whole_turn.CHECK_POINTS`` carrier turns, and the turn (rad).
    min_angle_ebf, min_angle_bef, min_angle_bef_turn : float
        Smallest angles EBF and BEF (rad) and where BEF's is (rad).
    correction : float
        k of eq (12) by the library's quadrature.
    min_curvature : tuple of 4 float
        Smallest a kappa of sun, first intermediate, second intermediate, planet (``CURVES``).
    curvature_floor : float or None
        The least a kappa the curvature rows held: ``CURVATURE_FLOOR`` (convex), -``CONCAVITY_LIMIT``
        (shaper-cut hollows), None (rows off); ``convexity_note`` says why, with the numbers, when not convex.
    active_bounds : tuple of ActiveBound
        Every named bound the NLP's solution sits on (``solve.active``), in the NLP's units.
    poses, carrier_turns : ndarray, shapes (4, 3) and (4,)
        The key poses (mm, rad) and carrier turns (rad) the design meets: the problem's, or those it chose
        inside their bands.
    solved : Solution or None
        The solve layer's solution it was read from, while an exchange continues it from its multipliers.
    multipliers : Multipliers or None
        That solution's multipliers, kept with the design (in a lane's result too): a re-solve that continues
        the design starts from them.
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
    active_bounds: tuple[ActiveBound, ...]
    poses: np.ndarray
    carrier_turns: np.ndarray
    curvature_floor: float | None = None
    convexity_note: str = ""
    solved: Solution | None = field(default=None, repr=False, compare=False)
    multipliers: Multipliers | None = field(default=None, repr=False, compare=False)


def reach(problem: FiveBarProblem) -> float:
    """The problem's own size (mm): the largest distance of a key pose or return point from O."""
    return float(np.hypot(*np.vstack([problem.poses[:, :2], problem.return_points]).T).max())


def length_unit(problem: FiveBarProblem) -> float:
    """The NLP's unit of length (mm): the power of ten at or below the reach (100 mm on the bundled
    example). Lengths of order one keep IPOPT's tolerances and the bounds on lengths (1e-3 of the unit)
    relative to the problem, and a problem scaled by a power of ten is the same NLP."""
    return float(10.0 ** np.floor(np.log10(reach(problem))))


@dataclass(frozen=True)
class DesignNLP:
    """The NLP of one problem with room for ``capacity`` exchange slots, and how a design maps onto it.

    The parameters are the start's assembly branch (+1 or -1) and, per exchange slot, its carrier turn
    and spline basis rows of orders 0-3. A slot left empty gets free rows (``bounds``), so it
    constrains nothing; so do the curvature rows when switched off. An NLP built without them
    (``curvature_rows`` False) solves only with them off.
    """

    layout: NLPLayout
    problem: FiveBarProblem
    fixed_points: int            # grid points before the exchange slots
    capacity: int
    unit: float                  # mm per NLP length unit (``length_unit``)
    curvature_rows: bool = True

    @property
    def grid_blocks(self) -> tuple[str, ...]:
        """The blocks of rows along the grid (``GRID_BLOCKS``) this NLP has."""
        return GRID_BLOCKS if self.curvature_rows else tuple(b for b in GRID_BLOCKS if b not in CURVATURE_BLOCKS)

    def bounds(self, added: int, curvature_floor: float | None, least_curvature: float,
               closure_in_quality: bool = False) -> Bounds:
        """The bounds of a solve with the first ``added`` exchange slots in use, the curvature rows holding
        a kappa >= ``curvature_floor`` (None: the rows off, u held at ``least_curvature``), and t held below
        sin^2 of the angle EBF too when ``closure_in_quality`` (the max-min of both angles: a start for the
        max-min of the transmission angle alone)."""
        if curvature_floor is not None and not self.curvature_rows:
            raise ValueError("a curvature floor for an NLP built without the curvature rows")
        bounds = self.layout.bounds()
        if not closure_in_quality:
            bounds.free_rows("closure_quality")
        for name in self.grid_blocks:
            bounds.free_rows(name, slice(self.fixed_points + added, None))
        if curvature_floor is None and self.curvature_rows:
            for name in CURVATURE_BLOCKS:
                bounds.free_rows(name)
        return bounds.fix("least_curvature", least_curvature if curvature_floor is None else curvature_floor)

    def parameters(self, branch: float, added_turns: np.ndarray) -> dict:
        """The parameter values for a start's branch and the exchange slots' carrier turns (rad)."""
        turns = np.r_[added_turns, np.zeros(self.capacity - len(added_turns))]
        n = self.problem.spline_count
        return {"branch": branch, "added_turns": turns,
                **{f"added_basis_{order}": basis_matrix(turns, n, order).T for order in range(4)}}

    def start(self, mech: FiveBar, relative: RelativeAngle, stroke: ReturnStroke, reached: np.ndarray,
              poses: np.ndarray, turns: np.ndarray) -> dict:
        """The variables of a design whose return points stand at ``reached`` (mm) and whose key poses are
        ``poses`` (mm, rad) at carrier turns ``turns``; t, k and u start at the design's own transmission
        quality, correction factor and least a kappa on the NLP's grid."""
        unit = self.unit
        check = whole_turn(mech, relative, np.linspace(0, TWO_PI, GRID_POINTS, endpoint=False))
        chosen = np.c_[poses[:, :2] / unit, poses[:, 2], turns]
        return {**{name: chosen[i, q] for name, (i, q) in self.key_blocks().items()},
                "carrier_length": mech.carrier_length / unit, "carrier_angle": mech.carrier_angle,
                "rod_length": mech.rod_length / unit, "hinge_b": mech.hinge_b / unit,
                "receiving_length": mech.receiving_length / unit, "plate_point_e": mech.e_local / unit,
                "plate_point_f": mech.f_local / unit, "relative_angle_start": relative.rho1,
                "spline_values": relative.coefficients[1:],
                "return_stroke": np.stack([stroke.carrier_turns, stroke.directions, *(reached.T / unit)]),
                "quality": np.nanmin(check["bef"]), "correction": check["correction"],
                "least_curvature": np.nanmin(check["curvature"])}

    def key_blocks(self) -> dict[str, tuple[int, int]]:
        """Name -> (pose, quantity) of every banded key-pose quantity (``key_pose_entries``)."""
        bands = self.problem.pose_bands
        if bands is None:
            return {}
        return {bands.field(self.problem.labels, int(i), int(q)): (int(i), int(q))
                for i, q in zip(*np.nonzero(bands.banded), strict=True)}

    def chosen_poses(self, solution: Solution) -> tuple[np.ndarray, np.ndarray]:
        """The key poses (mm, rad) and their carrier turns (rad) the solution chose: the problem's where exact."""
        chosen = np.c_[self.problem.poses, self.problem.carrier_turns]
        for name, (i, q) in self.key_blocks().items():
            chosen[i, q] = solution[name][0] * (self.unit if q < 2 else 1.0)
        return chosen[:, :3], chosen[:, 3]

    def design(self, solution: Solution, branch: float, curvature_floor: float | None) -> DesignSolution:
        """The solved design, evaluated again on its own over the whole turn."""
        problem, unit = self.problem, self.unit
        poses, key_turns = self.chosen_poses(solution)
        mech = FiveBar(carrier_length=float(solution["carrier_length"][0]) * unit,
                       carrier_angle=float(solution["carrier_angle"][0]),
                       rod_length=float(solution["rod_length"][0]) * unit, hinge_b=solution["hinge_b"] * unit,
                       receiving_length=float(solution["receiving_length"][0]) * unit,
                       e_local=solution["plate_point_e"] * unit, f_local=solution["plate_point_f"] * unit,
                       branch=branch)
        relative = RelativeAngle(float(solution["relative_angle_start"][0]), np.r_[0.0, solution["spline_values"]])
        turns, directions, *reached = solution["return_stroke"]
        stroke = ReturnStroke(turns, relative.evaluate(turns), directions)
        check = whole_turn(mech, relative)
        at_return = mech.forward(stroke.carrier_turns, stroke.relative_angles)["p"]
        ebf, bef = int(np.argmin(check["ebf"])), int(np.argmin(check["bef"]))
        knot_sides = whole_turn(mech, relative, knot_left_sides(problem.spline_count))["curvature"]
        return DesignSolution(
            mech, relative, stroke, np.column_stack(reached) * unit, solution.objective, solution.iterations,
            solution.status, quality=float(solution["quality"][0]),
            return_misses_mm=np.linalg.norm(at_return - problem.return_points, axis=1),
            min_closure_margin=float(check["ebf"][ebf]), min_closure_turn=float(check["turns"][ebf]),
            min_angle_ebf=float(np.arcsin(np.sqrt(check["ebf"][ebf]))),
            min_angle_bef=float(np.arcsin(np.sqrt(min(check["bef"][bef], 1.0)))),
            min_angle_bef_turn=float(check["turns"][bef]), correction=check["correction"],
            min_curvature=tuple(float(v) for v in np.fmin(check["curvature"].min(axis=1), knot_sides.min(axis=1))),
            active_bounds=solution.active_bounds(), poses=poses, carrier_turns=key_turns,
            curvature_floor=curvature_floor,
            convexity_note="" if curvature_floor is not None else "curvature rows off", solved=solution,
            multipliers=solution.multipliers())


def key_pose_entries(nlp: NLPBuilder, problem: FiveBarProblem, unit: float) -> np.ndarray:
    """The key poses' x, y (in ``unit``), plate direction and carrier turn (rad), shape (4, 4): a float where the
    problem fixes the value, a variable within its band (named as the file names it) where it gives a band."""
    key = np.empty((4, 4), dtype=object)
    exact = np.c_[problem.poses[:, :2] / unit, problem.poses[:, 2], problem.carrier_turns]
    bands = problem.pose_bands
    to_nlp = np.array([unit, unit, 1.0, 1.0])
    for i in range(4):
        for q in range(4):
            if bands is None or not bands.banded[i, q]:
                key[i, q] = float(exact[i, q])
                continue
            name = bands.field(problem.labels, i, q)
            low, high = bands.low[i, q] / to_nlp[q], bands.high[i, q] / to_nlp[q]
            key[i, q] = nlp.variables(name, 1, low, high, high - low, ((name, "lower"), (name, "upper")))
    return key


def build_nlp(problem: FiveBarProblem, capacity: int = ADDED_CAPACITY, curvature_rows: bool = True) -> DesignNLP:
    """The design NLP of ``problem`` with room for ``capacity`` exchange slots; without the curvature rows where
    ``curvature_rows`` is False (the NLP of the solves that hold no curvature: 400 of the bundled example's 1,052
    rows fewer, and an IPOPT iteration about 30 % cheaper than with the rows there but free)."""
    n, m = problem.spline_count, len(problem.return_points)
    unit = length_unit(problem)
    targets = problem.return_points / unit
    nlp = NLPBuilder()

    l1 = nlp.variables("carrier_length", lower=1e-3)
    theta11 = nlp.variables("carrier_angle")
    l2 = nlp.variables("rod_length", lower=1e-3)
    b = nlp.variables("hinge_b", 2)
    l4 = nlp.variables("receiving_length", lower=1e-3)
    e_local = nlp.variables("plate_point_e", 2)
    f_local = nlp.variables("plate_point_f", 2)
    rho1 = nlp.variables("relative_angle_start")
    q = ca.vertcat(0, nlp.variables("spline_values", n - 1))
    exact = problem.return_tolerance_mm == 0
    stroke_low, stroke_high = np.full((4, m), -np.inf), np.full((4, m), np.inf)
    if exact:
        stroke_low[2:], stroke_high[2:] = targets.T, targets.T
    ret = nlp.variables("return_stroke", (4, m), stroke_low, stroke_high)
    floor = 0.0 if problem.min_transmission_angle is None else float(np.sin(problem.min_transmission_angle) ** 2)
    quality = nlp.variables("quality", lower=floor, scale=max(floor, 1e-2),
                            names=None if problem.min_transmission_angle is None else
                            (("conditions.min_transmission_angle_deg", "lower"), None))
    correction = nlp.variables("correction", lower=0.0)
    least_curvature = nlp.variables("least_curvature", lower=-CONCAVITY_LIMIT, upper=-CONCAVITY_LIMIT)

    key = key_pose_entries(nlp, problem, unit)
    branch = nlp.parameters("branch")
    added_turns = nlp.parameters("added_turns", capacity)
    added_basis = [nlp.parameters(f"added_basis_{order}", (n, capacity)) for order in range(4)]

    q0 = basis_matrix(np.zeros(1), n)[0]

    def rho(c):
        return rho1 + c + ca.dot(ca.vertcat(*basis(c, n, 0, CASADI)), q) - ca.dot(ca.DM(q0), q)

    def rho_at_key(i: int):
        turn = key[i, 3]
        if isinstance(turn, float):          # an exact turn: the basis is a constant row
            return rho1 + ca.dot(ca.DM(basis_matrix(np.array([turn]), n)[0] - q0), q) + turn
        return rho(turn)

    plate = ca.vertcat(e_local, f_local)
    closure, assembly = casadi_function(fivebar_pose_closure), casadi_function(fivebar_assembly_sine)
    positions = [(ca.vertcat(*key[i, :3]), key[i, 3], rho_at_key(i)) for i in range(4)]
    positions += [(ca.vertcat(ret[2:4, j], ret[1, j]), ret[0, j], rho(ret[0, j])) for j in range(m)]
    residuals, sides = [], []
    for pose, c, angle in positions:
        theta1 = theta11 - c
        residuals.append(closure(pose, plate, b, ca.vertcat(l1, l2, l4), ca.vertcat(theta1, theta1 + angle)))
        sides.append(branch * assembly(pose, plate, b, l4))
    labels = [*problem.labels, *problem.return_labels]
    sqrt_margin = np.sqrt(problem.min_closure_margin)
    nlp.constraints("pose_closure", ca.vertcat(*residuals), 0.0, 0.0)
    nlp.constraints("assembly", ca.vertcat(*sides), sqrt_margin, np.inf, sqrt_margin,
                    [((f"assembly at {label}", "lower"), None) for label in labels])

    fixed = np.r_[np.linspace(0, TWO_PI, GRID_POINTS, endpoint=False), knot_left_sides(n)]
    grid = ca.vertcat(ca.DM(fixed), added_turns)
    points = len(fixed) + capacity
    rows = [ca.vertcat(ca.DM(basis_matrix(fixed, n, order)), added_basis[order].T) for order in range(4)]
    rho_grid = rho1 + grid + ca.mtimes(rows[0], q) - ca.dot(ca.DM(q0), q)
    theta1_grid = theta11 - grid
    # the rows of a grid point depend on the variables through its crank angles and rho', rho'', rho''', the
    # link lengths and the ground's angle: the Hessian of the Lagrangian goes through them (``NLPBuilder.lifted``)
    cranks = nlp.lifted("grid_cranks", ca.horzcat(theta1_grid, theta1_grid + rho_grid).T)
    derivatives = nlp.lifted("grid_derivatives", ca.horzcat(1 + ca.mtimes(rows[1], q), ca.mtimes(rows[2], q),
                                                            ca.mtimes(rows[3], q)).T)
    slope = derivatives[0, :].T
    lengths = nlp.lifted("lengths", ca.vertcat(l1, l2, ca.norm_2(e_local - f_local), l4, ca.norm_2(b)))
    crank = ca.vertcat(cranks, ca.repmat(nlp.lifted("ground_angle", ca.atan2(b[1], -b[0])), 1, points))
    along_grid = ca.repmat(lengths, 1, points), crank
    margins = casadi_function(fivebar_triangle_margins).map(points)(*along_grid)
    margin, transmission = margins[0, :].T, margins[1, :].T
    low_ratio, high_ratio = problem.ratio_bounds
    nlp.constraints("closure_margin", margin, problem.min_closure_margin, np.inf, problem.min_closure_margin,
                    (("min_closure_margin", "lower"), None))
    nlp.constraints("transmission_quality", transmission - quality, 0.0, np.inf)
    nlp.constraints("closure_quality", margin - quality, 0.0, np.inf)
    nlp.constraints("slope", slope, 1 / high_ratio, 1 / low_ratio, 1 / high_ratio,
                    (("ratio", "upper"), ("ratio", "lower")))
    if curvature_rows:
        curvature = casadi_function(train_pitch_curvature).map(points)(derivatives,
                                                                        ca.repmat(correction, 1, points))[1]
        for k, (name, curve) in enumerate(zip(CURVATURE_BLOCKS, CURVES, strict=True)):
            nlp.constraints(name, curvature[k, :].T - least_curvature, 0.0, np.inf, CURVATURE_FLOOR,
                            ((f"a kappa of the {curve} pitch curve", "lower"), None))
    pressure = pressure_rows(derivatives, correction, problem.gearing)
    for k, name in enumerate(PRESSURE_BLOCKS):
        nlp.constraints(name, pressure[k, :].T, -np.inf, 0.0, 1.0, (None, (PRESSURE_LIMIT, "upper")))

    spans = panels(knots(n), count=n, nodes=QUADRATURE_NODES)
    slopes = nlp.lifted("quadrature_slopes", 1 + ca.mtimes(ca.DM(basis_matrix(spans.nodes.ravel(), n, 1)), q))
    root_slope = ca.sqrt(slopes)
    nlp.constraints("correction_closure", correction * ca.dot(ca.DM(spans.weights.ravel()), root_slope) - TWO_PI,
                    0.0, 0.0)
    nlp.constraints("return_order", ca.vertcat(ret[0, 0] - key[-1, 3], ca.diff(ret[0, :].T), TWO_PI - ret[0, m - 1]),
                    MIN_STEP, np.inf, MIN_STEP)
    banded_turns = [i for i in range(1, 4) if not isinstance(key[i, 3], float)]
    if banded_turns:        # banded turns keep their order (their bands do not overlap) and a step between poses
        nlp.constraints("key_order", ca.vertcat(*(key[i, 3] - key[i - 1, 3] for i in banded_turns)), MIN_STEP,
                        np.inf, MIN_STEP)
    required = [row for row in problem.requirements.scaled(unit).rows(list(key[:, 0]), list(key[:, 1]),
                                                                        problem.stroke_direction)
                if not isinstance(row[1], float)]     # one between exact poses was checked when the file was read
    for name in dict.fromkeys(row[0] for row in required):
        rows_of = [row for row in required if row[0] == name]
        nlp.constraints(name, ca.vertcat(*[row[1] for row in rows_of]), [row[2] for row in rows_of],
                        [row[3] for row in rows_of], 1.0, ((name, "lower"), (name, "upper")))

    e1, f1 = casadi_function(fivebar_plate_hinges)(ca.vertcat(*key[0, :3]), plate)
    ranged = {"ep": ca.norm_2(e_local), "fp": ca.norm_2(f_local), "x_e": e1[0], "x_f": f1[0]}
    for key, (low, high) in problem.ranges.items():
        nlp.constraints(f"ranges.{key}", ranged[key], low / unit, high / unit, max(abs(low), abs(high)) / unit,
                        ((f"ranges.{key}", "lower"), (f"ranges.{key}", "upper")))
    # |P_j' - P_j|^2 / (2 tol) <= tol / 2: the row's units are lengths near the bound (a violation of IPOPT's
    # 1e-12 is 1e-12 of the NLP's unit there, where the squared distance would make it 1e-12 / (2 tol))
    tolerance = problem.return_tolerance_mm / unit
    scale = 1.0 if exact else 1 / (2 * tolerance)
    nlp.constraints("return_misses", scale * ca.sum1((ret[2:4, :] - targets.T) ** 2).T, -np.inf,
                    np.inf if exact else tolerance / 2, tolerance / 2, (None, (RETURN_TOLERANCE, "upper")))

    objective = -quality + BENDING_WEIGHT * ca.mtimes([q.T, ca.DM(bending_matrix(n)), q])
    return DesignNLP(nlp.build(objective), problem, len(fixed), capacity, unit, curvature_rows)

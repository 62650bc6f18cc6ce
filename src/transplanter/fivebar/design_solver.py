"""The design NLP of one problem as one IPOPT solver, reused for every start and exchange round: the
refinement of a region candidate, its attempt at convex pitch curves and the move of a return point to
another pass of P. The solves that hold no curvature (``without_hold``'s) take a second solver, built at the
first of them, of the NLP without the curvature rows.

Between grid points the quality, rho' and the curvatures may dip: each solve is checked on
``whole_turn``'s fine grid by independent forward kinematics and the library's quadrature of k, and
solved again from the last design with the worst carrier turns added to the grid (``solve.exchange``)
until the fine grid holds (the quality to ``QUALITY_GAP`` of t), each round from the last one's
multipliers too (``Solver.solve``'s ``continues``: 6-22 iterations a round instead of 21-29). The added
turns, the start's assembly branch and the start itself are inputs of a solve, not of the NLP's
expressions, so one solver serves every start and round. The turns an exchange added are offered to
every later start from its first solve (those the design sits on first: ``handed_turns``): each row holds a
condition the whole turn must meet anyway, so they change no solution, and starts that end in the same
mechanism need one round, not three.
"""
from __future__ import annotations

import copy
import dataclasses

import numpy as np

from transplanter.errors import SolverError
from transplanter.fivebar.candidate import Candidate
from transplanter.fivebar.handed_turns import handed_turns
from transplanter.fivebar.nlp import (
    ADDED_CAPACITY,
    CONCAVITY_LIMIT,
    CURVATURE_FLOOR,
    DesignNLP,
    DesignSolution,
    build_nlp,
)
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.reached_optima import ReachedOptimum, reached
from transplanter.fivebar.return_stroke import ReturnStroke
from transplanter.fivebar.whole_turn import CURVES, whole_turn
from transplanter.solve import Solver, StallRule, exchange, periodic_peaks
from transplanter.trains.pressure_angle import PRESSURE_GAP, pressure_excess

EXCHANGE_ROUNDS = 6
#: The fine check adds carrier turns where the quality falls below t by more than this fraction ...
QUALITY_GAP = 1e-3
#: ... where the closure margin falls below its floor by more than this fraction of it (a tenth of what the
#: verification allows: the floor binds wherever the transmission angle is bought with the angle EBF) ...
CLOSURE_GAP = 1e-7
#: ... or where a kappa falls below the value it is held at by more than this fraction of that value's size.
CURVATURE_GAP = 1e-3
#: Iterations each solve of the attempt at convex curves may take, from the design held at -CONCAVITY_LIMIT.
CONVEX_ATTEMPT_ITERATIONS = 25
#: A start that fails can crawl for hundreds of iterations with rows off by several percent (steps cut again
#: and again by the line search), or with IPOPT regularising the Hessian by 1e9 to 1e13 at nearly every
#: iteration (each such iteration takes several factorisations: the bundled example's first start spends a
#: fifth to a third of its 4-5 s of CPU on its last 16). Solves that succeed keep their rows within this rule.
#: They can pass through such a phase too, so its part is set well beyond them: of 347 recorded five-bar solves
#: that succeeded (the five-bar, solve and scale tests, the bundled examples) one was regularised by 1e9 or more
#: for 9 iterations in a row (and by 1e8 for 24, then converged at iteration 116), none other for more than 1;
#: the 8 failures it stops had runs of 18-31.
STALL = StallRule(violation=1e-3, iterations=100, regularization=1e9, regularized_iterations=15)


class HollowError(SolverError):
    """A start from which IPOPT finds no design with the pitch curves held to hollows a shaper cuts;
    ``reason`` says how it ended (``DesignSolver.without_hold`` adds what the curves are without the hold)."""

    def __init__(self, reason: str, status: str):
        super().__init__(reason, status)
        self.reason = reason


class DesignSolver:
    """The design NLP of ``problem`` as one solver. ``builds`` counts how often it was built: once, unless
    the exchange needs more than ``ADDED_CAPACITY`` slots (it is then rebuilt with twice the room)."""

    def __init__(self, problem: FiveBarProblem):
        self.problem = problem
        self.builds = 0
        self.exchange_turns = np.empty(0)     # turns earlier exchanges added (rad), offered to later starts
        self._build(ADDED_CAPACITY)

    def _build(self, capacity: int) -> None:
        self.nlp: DesignNLP = build_nlp(self.problem, capacity)
        self.solver = Solver("fivebar_design", self.nlp.layout, stall=STALL)
        self._without_curvature: tuple[DesignNLP, Solver] | None = None      # built at its first solve
        self.builds += 1
        self.reached: tuple[ReachedOptimum, ...] = ()     # this solver's refinements (``refine``)
        self.repeats = 0                                   # refinements taken from an earlier one

    def twin(self) -> DesignSolver:
        """A solver in this one's state that shares its built NLP and IPOPT Functions (no build): what each
        solve changes, the exchange turns, the refinements it finished and a rebuild with more room, stays
        each one's own."""
        return copy.copy(self)

    def solve(self, start: Candidate, added_turns=(), warm: DesignSolution | None = None,
              curvature_floor: float | None = None, iteration_limit: int | None = None,
              closure_in_quality: bool = False, continues: bool = False) -> DesignSolution:
        """Solve with the start's assembly branch and the exchange points ``added_turns`` (rad), from the
        start's own dimensions or from the design ``warm`` (a previous round's, and its multipliers too when
        the solve ``continues`` it: the same NLP with rows added or a start moved), with the four curves held
        to a kappa >= ``curvature_floor`` (None: the rows off); ``iteration_limit`` stops IPOPT early."""
        added_turns = np.asarray(added_turns, float)
        while len(added_turns) > self.nlp.capacity:
            self._build(2 * self.nlp.capacity)
        nlp, solver, branch = self.nlp_for(curvature_floor), self.solver_for(curvature_floor), float(start.mech.branch)
        if warm is None:
            assert start.relative_angle is not None and start.stroke is not None, "a feasible region candidate"
            poses, turns = start.key_poses(self.problem)
            values = nlp.start(start.mech, start.relative_angle, start.stroke, self.problem.return_points, poses, turns)
        else:
            values = nlp.start(warm.mech, warm.relative_angle, warm.stroke, warm.reached_return_points, warm.poses,
                               warm.carrier_turns)
        solution = solver.solve(
            values, nlp.bounds(len(added_turns), curvature_floor, float(values["least_curvature"]), closure_in_quality),
            nlp.parameters(branch, added_turns), iteration_limit,
            failure=f"{self.problem.source}: the design NLP did not converge from the region candidate",
            continues=warm.multipliers if continues and warm is not None and warm.multipliers is not None
            and warm.multipliers.fits(nlp.layout) else None)
        return nlp.design(solution, branch, curvature_floor)

    def nlp_for(self, curvature_floor: float | None) -> DesignNLP:
        """The NLP a solve with ``curvature_floor`` takes: without the curvature rows where it is None."""
        return self._nlp_and_solver(curvature_floor)[0]

    def solver_for(self, curvature_floor: float | None) -> Solver:
        """The IPOPT solver of ``nlp_for(curvature_floor)``."""
        return self._nlp_and_solver(curvature_floor)[1]

    def _nlp_and_solver(self, curvature_floor: float | None) -> tuple[DesignNLP, Solver]:
        if curvature_floor is not None:
            return self.nlp, self.solver
        if self._without_curvature is None:
            nlp = build_nlp(self.problem, self.nlp.capacity, curvature_rows=False)
            self._without_curvature = nlp, Solver("fivebar_design_without_curvature", nlp.layout, stall=STALL)
        return self._without_curvature

    def refine(self, start: Candidate) -> DesignSolution:
        """The largest smallest transmission angle from ``start`` with every pitch curve a shaper can cut:
        a kappa >= -``CONCAVITY_LIMIT``; a ``HollowError`` naming IPOPT's end when it fails there. A start
        whose first solve reaches the optimum of an earlier refinement of this solver, offered the same
        exchange turns, ends as that one did (``fivebar.reached_optima``)."""
        turns, branch = self.exchange_turns, float(start.mech.branch)
        try:
            first = self.solve(start, turns, curvature_floor=-CONCAVITY_LIMIT, closure_in_quality=True)
        except SolverError as error:
            raise _hollow(error) from None
        assert first.solved is not None, "a solve's design carries its solution"
        known = reached(self.reached, turns, branch, first.solved.x)
        if known is not None:
            self.exchange_turns, self.repeats = known.turns_after, self.repeats + 1
            if isinstance(known.outcome, HollowError):
                raise HollowError(known.outcome.reason, known.outcome.status)
            assert isinstance(known.outcome, DesignSolution)
            return known.outcome
        outcome: DesignSolution | HollowError
        try:
            both = self._exchange(start, -CONCAVITY_LIMIT, closure_in_quality=True, first=first)
            outcome = self._exchange(start, -CONCAVITY_LIMIT, warm=both)
        except SolverError as error:
            outcome = _hollow(error)
        self.reached = (*self.reached, ReachedOptimum(turns, branch, first.solved.x, outcome, self.exchange_turns))
        if isinstance(outcome, HollowError):
            raise HollowError(outcome.reason, outcome.status)
        return outcome

    def without_hold(self, start: Candidate) -> str:
        """What ``start``'s design is without the curvature hold that ``refine`` failed with: the least a kappa
        of each curve (a hollow that only gears many times the mechanism's size could carry), or how IPOPT
        ended. A re-solve that only words a message: asked for where no start gave a design."""
        try:
            return f"without that hold: {curvature_text(self._exchange(start, None))}"
        except SolverError as error:
            return f"without that hold IPOPT ended with {error.status}"

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
        pass of P by it: ``return_passes.other_passes``) instead of its own, starting from ``design``'s
        multipliers (57, 52 and 41 iterations on the bundled example's three moves instead of 93, 33 and 69;
        the same designs to 1e-13 of the objective)."""
        turns = design.stroke.carrier_turns.copy()
        turns[point] = turn
        rho = design.relative_angle.evaluate(turns)
        state = design.mech.forward(turns, rho)
        directions, reached = design.stroke.directions.copy(), design.reached_return_points.copy()
        directions[point], reached[point] = state["direction"][point], state["p"][point]
        warm = dataclasses.replace(design, stroke=ReturnStroke(turns, rho, directions), reached_return_points=reached)
        return self._exchange(start, -CONCAVITY_LIMIT, warm=warm, continues_warm=True)

    def _exchange(self, start: Candidate, curvature_floor: float | None, warm: DesignSolution | None = None,
                  iteration_limit: int | None = None, closure_in_quality: bool = False,
                  first: DesignSolution | None = None, continues_warm: bool = False) -> DesignSolution:
        """``solve`` with the carrier turns where the fine check finds sin^2 of the transmission angle below t,
        the closure margin below its floor, or rho', a pressure angle or a curvature (below
        ``curvature_floor``) out of bounds,
        added to its grid (``solve.exchange``); ``first``: its first solve, done already; ``continues_warm``: the
        first solve starts from ``warm``'s multipliers too (later rounds always start from their previous one's)."""
        low, high = 1 / self.problem.ratio_bounds[1], 1 / self.problem.ratio_bounds[0]
        floor = self.problem.min_closure_margin

        def solve(turns: np.ndarray, previous: DesignSolution | None) -> DesignSolution:
            return self.solve(start, turns, previous, curvature_floor, iteration_limit, closure_in_quality,
                              continues=continues_warm or previous is not warm)

        def worst_turns(solution: DesignSolution) -> np.ndarray:
            check = whole_turn(solution.mech, solution.relative_angle)
            slope = check["slope"]
            quality = np.fmin(check["bef"], check["ebf"]) if closure_in_quality else check["bef"]
            shortfall = np.fmax.reduce([
                (solution.quality - quality) / max(solution.quality, QUALITY_GAP) - QUALITY_GAP,
                (floor - check["ebf"]) / floor - CLOSURE_GAP, (low - slope) / low, (slope - high) / high,
                pressure_excess(check["leans"], self.problem.gearing) - PRESSURE_GAP,
                *([] if curvature_floor is None else
                  (curvature_floor - check["curvature"]) / abs(curvature_floor) - CURVATURE_GAP)])
            return check["turns"][periodic_peaks(shortfall)]

        solution, added = exchange(solve, worst_turns, self.exchange_turns, EXCHANGE_ROUNDS, warm, first)
        assert solution.solved is not None, "a solve's design carries its solution"
        nlp = self.nlp_for(curvature_floor)
        self.exchange_turns = handed_turns(solution.solved, nlp.grid_blocks, nlp.fixed_points, added, nlp.capacity // 2)
        # a lane's result leaves the solution (and the NLP) behind; its multipliers, plain arrays, go with it
        return dataclasses.replace(solution, solved=None)


def _hollow(error: SolverError) -> HollowError:
    """``refine``'s failure: how IPOPT ended with the pitch curves held to hollows a shaper cuts."""
    return HollowError(f"IPOPT ended with {error.status} with the pitch curves held to a kappa >= "
                       f"{-CONCAVITY_LIMIT:g} (hollows a shaper cuts)", error.status)


def curvature_text(design: DesignSolution) -> str:
    return "least a kappa " + ", ".join(f"{curve} {value:.3f}"
                                        for curve, value in zip(CURVES, design.min_curvature, strict=True))


def concavity_text(design: DesignSolution) -> str:
    """The held design's least a kappa per curve, the tightest, and the cutter that follows."""
    tightest = int(np.argmin(design.min_curvature))
    stages = sorted({("sun -> first intermediate", "second intermediate -> planet")[k // 2]
                     for k, value in enumerate(design.min_curvature) if value < 0})
    return (f"held to a kappa >= {-CONCAVITY_LIMIT:g} (a hollow no tighter than a / {CONCAVITY_LIMIT:g}): "
            f"{curvature_text(design)}, tightest the {CURVES[tightest]}; concave, so shaper-cut: "
            + ", ".join(stages))

"""The one place an NLP meets IPOPT (``casadi.nlpsol``): one option set, one rule for what counts as
success, and solutions read back by block name.

Options: IPOPT's adaptive barrier update, a stationarity tolerance ``tolerance`` (1e-10 unless a caller
needs a tighter one) and a constraint violation tolerance of 1e-12, at most ``max_iterations``; no
parameter multipliers (casadi then skips building the NLP's gradient function); the package's KKT
factorisation where it is compiled (``kkt_solver``). Success is
``ACCEPTED``; any other end, or a stall (``solve.stall``), raises a ``SolverError`` naming it.

A re-solve that continues a nearby optimum (the same NLP with rows added, as an exchange round) starts
from that optimum's multipliers too (IPOPT's warm start, ``WARM_START``): with x alone IPOPT starts its
multipliers afresh and needs 21-29 iterations a round; with them, 6-22 (49 against 94 in four) on the
bundled five-bar example. Its warm-start twin shares the derivative functions of the solver's own
(built once, 0.02 s for the twin).

CasADi loads its own OpenBLAS with IPOPT, at the first ``nlpsol``; unless the user has set
``OPENBLAS_NUM_THREADS``, it is given one thread: the KKT systems here are a few hundred rows, and the
idle threads spin (the main job took 60 s wall, 28 s of it system time, against 40 s with one thread).
"""
from __future__ import annotations

import os
from collections.abc import Mapping
from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter.errors import SolverError
from transplanter.solve.active import ActiveBound, active_bounds
from transplanter.solve.kkt_solver import kkt_solver_options
from transplanter.solve.layout import Bounds, NLPLayout
from transplanter.solve.multipliers import Multipliers
from transplanter.solve.stall import IterationWatch, StallRule

#: IPOPT return statuses that count as a solution (every result is checked again independently).
ACCEPTED = frozenset({"Solve_Succeeded", "Solved_To_Acceptable_Level"})
TOLERANCE = 1e-10
CONSTRAINT_TOLERANCE = 1e-12
MAX_ITERATIONS = 1000

#: IPOPT's options for a start from an optimum's multipliers: the given start is kept (not pushed into the
#: interior by the default 1e-3 of the bounds' distance).
WARM_START = {"ipopt.warm_start_init_point": "yes", "ipopt.warm_start_bound_push": 1e-9,
              "ipopt.warm_start_mult_bound_push": 1e-9}

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")     # read when casadi loads IPOPT's OpenBLAS (docstring)


def ipopt_options(tolerance: float, max_iterations: int) -> dict:
    """The option set every solver of the package uses."""
    return {"ipopt.print_level": 0, "ipopt.sb": "yes", "print_time": False, "ipopt.tol": tolerance,
            "ipopt.constr_viol_tol": CONSTRAINT_TOLERANCE, "ipopt.max_iter": max_iterations,
            "ipopt.mu_strategy": "adaptive", "calc_lam_p": False, "no_nlp_grad": True, **kkt_solver_options()}


@dataclass(frozen=True)
class Solution:
    """A successful solve: values, constraint rows and multipliers, each readable by block name."""

    layout: NLPLayout
    bounds: Bounds
    x: np.ndarray
    g: np.ndarray
    lam_x: np.ndarray
    lam_g: np.ndarray
    objective: float
    iterations: int
    status: str

    def __getitem__(self, name: str) -> np.ndarray:
        """The values of variable block ``name``."""
        return self.layout.variables[name].read(self.x)

    def row(self, name: str) -> np.ndarray:
        """The values of constraint block ``name`` at the solution."""
        return self.layout.rows[name].read(self.g)

    def values(self) -> dict[str, np.ndarray]:
        """Every variable block's values, by name (a start for another solve)."""
        return {name: block.read(self.x) for name, block in self.layout.variables.items()}

    def multipliers(self) -> Multipliers:
        """Its multipliers, a start for a re-solve that continues it (``Solver.solve``'s ``continues``)."""
        return Multipliers(self.lam_x, self.lam_g)

    def active_bounds(self) -> tuple[ActiveBound, ...]:
        """The named bounds the solution sits on (``solve.active``)."""
        return active_bounds(self.layout, self.bounds, self.x, self.g, self.lam_x, self.lam_g)


class Solver:
    """One IPOPT solver of a layout, reused for every start: parameters and bounds change per solve,
    the expressions do not."""

    def __init__(self, name: str, layout: NLPLayout, tolerance: float = TOLERANCE,
                 max_iterations: int = MAX_ITERATIONS, stall: StallRule | None = None):
        self.layout, self.name = layout, name
        self.watch = IterationWatch(layout.g.shape[0], stall)
        self.options = {**ipopt_options(tolerance, max_iterations), "iteration_callback": self.watch}
        self.function = self._nlpsol(name, self.options)
        self._warm_function: ca.Function | None = None

    def _nlpsol(self, name: str, options: dict) -> ca.Function:
        layout = self.layout
        if layout.hessian is not None:
            options = {"hess_lag": layout.hessian, **options}
        if layout.jacobian is not None:
            options = {"jac_g": layout.jacobian, **options}
        return ca.nlpsol(name, "ipopt", {"x": layout.x, "p": layout.p, "f": layout.f, "g": layout.g}, options)

    def _warm(self) -> ca.Function:
        """The solver's twin that starts from given multipliers, on the solver's own derivative functions."""
        if self._warm_function is None:
            shared = {option: self.function.get_function(name) for option, name in
                      (("grad_f", "nlp_grad_f"), ("jac_g", "nlp_jac_g"), ("hess_lag", "nlp_hess_l"))
                      if name in self.function.get_function()}
            self._warm_function = self._nlpsol(f"{self.name}_warm", {**self.options, **WARM_START, **shared})
        return self._warm_function

    def ipopt_arguments(self, start: Mapping[str, object], bounds: Bounds,
                        parameters: Mapping[str, object] | None = None,
                        continues: Solution | Multipliers | None = None) -> dict[str, np.ndarray]:
        """IPOPT's arguments for a solve from ``start`` within ``bounds`` at ``parameters``; with ``continues``,
        its multipliers too (``lam_x0``, ``lam_g0``: those of bounds this solve lifts start at zero)."""
        layout = self.layout
        arguments = {"x0": layout.vector(start), "lbx": bounds.lbx, "ubx": bounds.ubx, "lbg": bounds.lbg,
                     "ubg": bounds.ubg}
        if layout.p.shape[0]:
            arguments["p"] = layout.parameter_vector(parameters or {})
        if continues is not None:
            if isinstance(continues, Solution):
                assert continues.layout is layout, "multipliers of this solver's own NLP"
                continues = continues.multipliers()
            assert continues.fits(layout), "multipliers sized for this solver's NLP"
            arguments["lam_x0"] = held_multipliers(continues.lam_x, bounds.lbx, bounds.ubx)
            arguments["lam_g0"] = held_multipliers(continues.lam_g, bounds.lbg, bounds.ubg)
        return arguments

    def solve(self, start: Mapping[str, object], bounds: Bounds | None = None,
              parameters: Mapping[str, object] | None = None, iteration_limit: int | None = None,
              failure: str = "the NLP did not converge",
              continues: Solution | Multipliers | None = None) -> Solution:
        """Solve from ``start`` (a value per variable block), within ``bounds`` (default: the declared
        ones), at ``parameters``; a ``SolverError`` starting with ``failure`` and naming the status (or
        the stall) when IPOPT does not succeed. ``continues``: a solution of this layout, or its multipliers, that
        start the solve (module docstring; those of bounds this solve lifts start at zero)."""
        layout = self.layout
        bounds = bounds or layout.bounds()
        arguments = self.ipopt_arguments(start, bounds, parameters, continues)
        function = self._warm() if continues is not None else self.function
        self.watch.watch(iteration_limit, bounds.lbg, bounds.ubg, layout.row_scales(), function)
        result = function(**arguments)
        stats = function.stats()
        status = stats["return_status"]
        if self.watch.stalled:
            status = self.watch.stall_text()
        if status not in ACCEPTED:
            raise SolverError(failure, status)
        x, g, lam_x, lam_g = (np.asarray(result[key]).ravel() for key in ("x", "g", "lam_x", "lam_g"))
        return Solution(layout, bounds, x, g, lam_x, lam_g, float(result["f"]), int(stats["iter_count"]), status)


def held_multipliers(multipliers: np.ndarray, lower: np.ndarray, upper: np.ndarray) -> np.ndarray:
    """``multipliers`` (CasADi's sign: negative on a lower bound, positive on an upper one) with those of a
    side that has no bound now set to zero."""
    lifted = ((multipliers < 0) & ~np.isfinite(lower)) | ((multipliers > 0) & ~np.isfinite(upper))
    return np.where(lifted, 0.0, multipliers)

"""IPOPT's iteration callback: stops a solve after an iteration limit, or when it has stalled: rows kept
off their bounds iteration after iteration while the line search crawls, or IPOPT adding a large
regularisation to the Hessian at every iteration (its inertia correction: the KKT matrix keeps the wrong
inertia, so each step is a heavily damped gradient step, and costs several factorisations)."""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np


@dataclass(frozen=True)
class StallRule:
    """A solve has stalled when some row stays off its bounds by more than ``violation`` of the row's
    scale for ``iterations`` iterations in a row, or (where ``regularization`` is given) when IPOPT adds at
    least ``regularization`` to the Hessian's diagonal (delta_w, its ``lg(rg)`` column) for
    ``regularized_iterations`` iterations in a row."""

    violation: float
    iterations: int
    regularization: float | None = None
    regularized_iterations: int = 1


def relative_violation(g: np.ndarray, lbg: np.ndarray, ubg: np.ndarray, scales: np.ndarray) -> float:
    """The largest amount by which a row lies outside its bounds, as a fraction of the row's scale (0:
    every row holds; NaN rows count as infinitely far)."""
    with np.errstate(invalid="ignore"):
        outside = np.fmax(lbg - g, g - ubg) / scales
    return float(np.max(np.where(np.isnan(g), np.inf, np.fmax(outside, 0.0)), initial=0.0))


class IterationWatch(ca.Callback):
    """Stops IPOPT after ``limit`` iterations (None: never) or on a stall by ``rule`` (None: never);
    ``watch`` arms it for one solve, ``stalled``, ``count`` and ``stall_text`` say afterwards what happened."""

    def __init__(self, rows: int, rule: StallRule | None):
        ca.Callback.__init__(self)
        self.rows, self.rule = rows, rule
        self.limit: int | None = None
        self.count, self.stalled, self.infeasible_run, self.next_look = 0, False, 0, 0
        self.lbg = self.ubg = self.scales = np.empty(0)
        self.solver: ca.Function | None = None
        self.construct("iteration_watch", {})

    def watch(self, limit: int | None, lbg: np.ndarray, ubg: np.ndarray, scales: np.ndarray,
              solver: ca.Function | None = None) -> None:
        """Arm for one solve by ``solver`` (the IPOPT Function this callback is given to, whose statistics
        hold the regularisation of the iterations so far; None: the regularisation is not watched)."""
        self.limit, self.lbg, self.ubg, self.scales, self.solver = limit, lbg, ubg, scales, solver
        self.count, self.infeasible_run, self.next_look, self.stalled = 0, 0, 0, False

    def regularized_run(self, threshold: float, most: int) -> int:
        """How many iterations in a row, up to the one just done, IPOPT regularised the Hessian by at least
        ``threshold`` (at most ``most`` counted; 0 when the solver's statistics do not tell)."""
        if self.solver is None:
            return 0
        sizes = self.solver.stats().get("iterations", {}).get("regularization_size", [])
        if len(sizes) != self.count:
            return 0
        regularized = np.asarray(sizes[-most:]) >= threshold
        return len(regularized) if regularized.all() else int(np.argmin(regularized[::-1]))

    def stall_text(self) -> str:
        """The stall that stopped the solve, in words."""
        rule = self.rule
        assert rule is not None and self.stalled, "a solve this watch stopped on a stall"
        if self.infeasible_run >= rule.iterations:
            held = f"a row off its bounds by more than {rule.violation:g} of its size for {rule.iterations}"
        else:
            held = (f"the Hessian regularisation at or above {rule.regularization:g} for "
                    f"{rule.regularized_iterations}")
        return f"a stall ({held} iterations in a row, after {self.count})"

    def get_n_in(self):
        return ca.nlpsol_n_out()

    def get_n_out(self):
        return 1

    def get_name_in(self, i):
        return ca.nlpsol_out(i)

    def get_name_out(self, i):
        return "stop"

    def get_sparsity_in(self, i):
        """The rows' values g only: an empty input is one CasADi neither converts nor passes each iteration."""
        if ca.nlpsol_out(i) == "g":
            return ca.Sparsity.dense(self.rows)
        return ca.Sparsity(0, 0)

    def eval(self, arg):
        self.count += 1
        rule = self.rule
        if rule is not None:
            g = np.asarray(arg[ca.nlpsol_out().index("g")]).ravel()
            violation = relative_violation(g, self.lbg, self.ubg, self.scales)
            self.infeasible_run = self.infeasible_run + 1 if not violation <= rule.violation else 0
            self.stalled = self.infeasible_run >= rule.iterations
            if rule.regularization is not None and self.count >= self.next_look:
                # the statistics hold every iteration so far: looked at again only when a run could be complete
                run = self.regularized_run(rule.regularization, rule.regularized_iterations)
                self.stalled |= run >= rule.regularized_iterations
                self.next_look = self.count + rule.regularized_iterations - run
        return [int(self.stalled or (self.limit is not None and self.count > self.limit))]

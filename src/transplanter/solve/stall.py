"""IPOPT's iteration callback: stops a solve after an iteration limit, or when it has stalled (rows kept
off their bounds iteration after iteration while the line search crawls)."""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np


@dataclass(frozen=True)
class StallRule:
    """A solve has stalled when some row stays off its bounds by more than ``violation`` of the row's
    scale for ``iterations`` iterations in a row."""

    violation: float
    iterations: int


def relative_violation(g: np.ndarray, lbg: np.ndarray, ubg: np.ndarray, scales: np.ndarray) -> float:
    """The largest amount by which a row lies outside its bounds, as a fraction of the row's scale (0:
    every row holds; NaN rows count as infinitely far)."""
    with np.errstate(invalid="ignore"):
        outside = np.fmax(lbg - g, g - ubg) / scales
    return float(np.max(np.where(np.isnan(g), np.inf, np.fmax(outside, 0.0)), initial=0.0))


class IterationWatch(ca.Callback):
    """Stops IPOPT after ``limit`` iterations (None: never) or on a stall by ``rule`` (None: never);
    ``watch`` arms it for one solve, ``stalled`` and ``count`` say afterwards what happened."""

    def __init__(self, variables: int, rows: int, rule: StallRule | None):
        ca.Callback.__init__(self)
        self.variables, self.rows, self.rule = variables, rows, rule
        self.limit: int | None = None
        self.count, self.stalled, self.infeasible_run = 0, False, 0
        self.lbg = self.ubg = self.scales = np.empty(0)
        self.construct("iteration_watch", {})

    def watch(self, limit: int | None, lbg: np.ndarray, ubg: np.ndarray, scales: np.ndarray) -> None:
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
        if self.rule is not None:
            g = np.asarray(arg[ca.nlpsol_out().index("g")]).ravel()
            violation = relative_violation(g, self.lbg, self.ubg, self.scales)
            self.infeasible_run = self.infeasible_run + 1 if not violation <= self.rule.violation else 0
            self.stalled = self.infeasible_run >= self.rule.iterations
        return [int(self.stalled or (self.limit is not None and self.count > self.limit))]

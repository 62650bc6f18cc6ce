"""A mechanism's built motion, written once over a backend, as the two callables a ``ToleranceModel`` holds.

``built_motion(lib, design, v, turn)`` gives the motion's rows of a built mechanism with dimensions ``v`` (by
name) at the turns of ``turn`` (the mechanism's data per turn), on ``generated.CASADI`` or
``generated.NUMPY``: the CasADi Function of one turn (for the exact Jacobian) and the numpy motion of N
built mechanisms by T turns (for the Monte Carlo) both come from it.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import casadi as ca
import numpy as np

from transplanter.generated import CASADI, NUMPY

BuiltMotion = Callable[[Any, Any, dict, Any], tuple]


def casadi_motion(name: str, built_motion: BuiltMotion, design: Any, names: tuple[str, ...],
                  turn_rows: int) -> ca.Function:
    """(dimensions (n,), the data of one turn (``turn_rows``,)) -> the rows of the built motion at that turn."""
    d, t = ca.SX.sym("dimensions", len(names)), ca.SX.sym("turn", turn_rows)
    rows = built_motion(CASADI, design, dict(zip(names, ca.vertsplit(d), strict=True)), ca.vertsplit(t))
    return ca.Function(name, [d, t], [ca.vertcat(*rows)])


@dataclass(frozen=True)
class SampledMotion:
    """The motion (N, rows, T) of N built mechanisms (dimensions (N, n) in ``names`` order) at the turns of
    ``turn_data`` (per-turn data, (rows of data, T)) by the numpy backend; a chain that does not close gives
    NaN, which the mechanism's conditions judge."""

    built_motion: BuiltMotion
    design: Any
    names: tuple[str, ...]
    turn_data: np.ndarray

    def __call__(self, dimensions: np.ndarray) -> np.ndarray:
        v = {name: dimensions[:, i, None] for i, name in enumerate(self.names)}
        with np.errstate(invalid="ignore"):
            return np.stack(np.broadcast_arrays(*self.built_motion(NUMPY, self.design, v, self.turn_data)), axis=1)

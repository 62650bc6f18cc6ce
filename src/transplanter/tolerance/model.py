"""What a mechanism hands the tolerance analysis: its dimensions and its motion as a function of them.

The motion of a built mechanism is a matrix (rows, T): one column per input angle of ``turns_deg`` (the key
poses first; ``whole_turn`` the columns that sample the whole turn evenly), rows 0-2 the plate reference
point P (x, y, mm) and the plate angle (rad); further rows are the mechanism's own (margins, hinge
positions) that its ``conditions`` read. The mechanism gives it twice from one formula written over a
backend, as generated code is:

- ``at_turn``, a CasADi Function (dimensions (n,), the mechanism's data of one turn, a column of
  ``turn_data``) -> the rows at that turn, built from the same generated closure the synthesis uses, so
  its Jacobian (CasADi's automatic differentiation) is exact;
- ``sampled``, numpy: dimensions (N, n) -> motion (N, rows, T) of N built mechanisms at once.

Dimensions are in ``dimensions`` order, each in its unit (mm or deg). ``conditions`` takes the motion of N
built mechanisms (N, rows, T) and their dimensions (N, n) and returns, per hard condition, which of them
violate it ((N,) booleans). ``backend_motion`` makes both from the formula.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Any

import casadi as ca
import numpy as np

from transplanter.generated import CASADI, NUMPY
from transplanter.tolerance.dimensions import Dimension

Conditions = Callable[[np.ndarray, np.ndarray], dict[str, np.ndarray]]


@dataclass(frozen=True)
class ToleranceModel:
    """A built mechanism's motion as a function of its manufactured dimensions (see the module docstring)."""

    title: str
    dimensions: tuple[Dimension, ...]
    at_turn: ca.Function
    turn_data: np.ndarray
    sampled: Callable[[np.ndarray], np.ndarray]
    turns_deg: np.ndarray
    key_labels: tuple[str, ...]
    whole_turn: slice
    conditions: Conditions
    point: str = "P"                # what rows 0-1 are, as reports and figures name it
    angle: str = "plate angle"      # what row 2 is

    @property
    def nominal(self) -> np.ndarray:
        return np.array([d.nominal for d in self.dimensions])

    @property
    def tolerances(self) -> np.ndarray:
        return np.array([d.tolerance for d in self.dimensions])

    @property
    def names(self) -> tuple[str, ...]:
        return tuple(d.name for d in self.dimensions)

    def with_dimensions(self, dimensions: tuple[Dimension, ...]) -> ToleranceModel:
        return replace(self, dimensions=dimensions)

    def evaluate(self, dimensions: np.ndarray) -> np.ndarray:
        """The motion (rows, T) of one built mechanism, by the CasADi Function."""
        turns = self.turn_data.shape[1]
        return np.asarray(self.at_turn.map(turns)(np.repeat(np.asarray(dimensions, float)[:, None], turns, 1),
                                                  self.turn_data))

    def jacobian(self) -> np.ndarray:
        """d motion / d dimensions at the nominal dimensions by automatic differentiation: (rows, T, n), per
        unit of each dimension."""
        x, data = ca.SX.sym("dimensions", len(self.dimensions)), ca.SX.sym("turn", self.turn_data.shape[0])
        rows = self.at_turn.size1_out(0)
        per_turn = ca.Function("motion_jacobian", [x, data], [ca.jacobian(self.at_turn(x, data), x)])
        turns = self.turn_data.shape[1]
        blocks = np.asarray(per_turn.map(turns)(np.repeat(self.nominal[:, None], turns, 1), self.turn_data))
        return blocks.reshape(rows, turns, len(self.dimensions))


@dataclass(frozen=True)
class SampledMotion:
    """The motion (N, rows, T) of N built mechanisms (dimensions (N, n)) by the numpy backend of ``formula``
    (``backend_motion``); a chain that does not close gives NaN, which the mechanism's conditions judge."""

    formula: Callable
    result: Any
    names: tuple[str, ...]
    turn_data: np.ndarray

    def __call__(self, dimensions: np.ndarray) -> np.ndarray:
        v = {name: dimensions[:, i, None] for i, name in enumerate(self.names)}
        with np.errstate(invalid="ignore"):
            return np.stack(np.broadcast_arrays(*self.formula(NUMPY, self.result, v, self.turn_data)), axis=1)


def backend_motion(name: str, formula: Callable, result, names: tuple[str, ...],
                   turn_data: np.ndarray) -> tuple[ca.Function, SampledMotion]:
    """``at_turn`` and ``sampled`` of a mechanism whose motion is ``formula(lib, result, v, turn)`` (``lib`` a
    backend of ``transplanter.generated``, ``v`` the dimensions by ``names``, ``turn`` a column of
    ``turn_data``) -> the rows."""
    d, g = ca.SX.sym("dimensions", len(names)), ca.SX.sym("turn", turn_data.shape[0])
    rows = formula(CASADI, result, dict(zip(names, ca.vertsplit(d), strict=True)), ca.vertsplit(g))
    return ca.Function(name, [d, g], [ca.vertcat(*rows)]), SampledMotion(formula, result, names, turn_data)

"""An NLP declared in named blocks: decision variables, parameters and constraint rows, each block
with its bounds, its scale and the names its bounds carry in reports; values are read back by name.

A block is added once and keeps its place: adding another block never moves the rows of those
already there, and nothing outside this module indexes the flat vectors IPOPT works on.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from transplanter.solve.lifted_hessian import lifted_hessian
from transplanter.solve.lifted_jacobian import lifted_jacobian

#: A bound's name in reports and the side of the reported quantity it limits ("lower" or "upper"), or
#: None for a bound no report names (an equality, a row that only keeps the NLP well posed).
BoundName = tuple[str, str] | None


@dataclass(frozen=True)
class Block:
    """Entries ``start`` .. ``start + size`` of a flat vector, read as an array of ``shape``
    (column-major, as CasADi's ``reshape``)."""

    name: str
    start: int
    shape: tuple[int, ...]

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    @property
    def slice(self) -> slice:
        return slice(self.start, self.start + self.size)

    def read(self, vector: np.ndarray) -> np.ndarray:
        values = np.asarray(vector, float).ravel()[self.slice]
        return values.reshape(self.shape, order="F") if len(self.shape) > 1 else values

    def flat(self, value) -> np.ndarray:
        """``value`` (a number, or an array of ``shape``) as this block's entries."""
        array = np.asarray(value, float)
        if array.ndim == 0:
            return np.full(self.size, float(array))
        if array.shape != self.shape and array.size != self.size:
            raise ValueError(f"block {self.name}: {array.shape} given for shape {self.shape}")
        return array.reshape(-1, order="F") if array.shape == self.shape else array.ravel()


@dataclass(frozen=True)
class BoundedBlock(Block):
    """A block of variables or constraint rows: default bounds, the size its distance from a bound is
    judged against (``scale``, per entry) and per entry the names of its lower and upper bound."""

    lower: np.ndarray = field(repr=False, default_factory=lambda: np.empty(0))
    upper: np.ndarray = field(repr=False, default_factory=lambda: np.empty(0))
    scale: np.ndarray = field(repr=False, default_factory=lambda: np.empty(0))
    names: tuple[tuple[BoundName, BoundName], ...] = ()


def _per_entry(names, size: int) -> tuple[tuple[BoundName, BoundName], ...]:
    """Bound names given once for a block, or once per entry, as one (lower, upper) pair per entry."""
    if names is None:
        return ((None, None),) * size
    if isinstance(names, tuple) and len(names) == 2 and all(n is None or isinstance(n[0], str) for n in names):
        return (names,) * size
    names = tuple(names)
    if len(names) != size:
        raise ValueError(f"{len(names)} bound names for {size} entries")
    return names


class NLPBuilder:
    """Collects named blocks; ``build`` fixes them into an ``NLPLayout``."""

    def __init__(self) -> None:
        self._variables: list[tuple[BoundedBlock, ca.SX]] = []
        self._parameters: list[tuple[Block, ca.SX]] = []
        self._rows: list[tuple[BoundedBlock, ca.SX]] = []
        self._lifted: list[tuple[ca.SX, ca.SX]] = []

    @staticmethod
    def _next(blocks: list) -> int:
        return blocks[-1][0].start + blocks[-1][0].size if blocks else 0

    @staticmethod
    def _check_new(name: str, *groups: list) -> None:
        if any(block.name == name for blocks in groups for block, _ in blocks):
            raise ValueError(f"block {name!r} declared twice")

    def variables(self, name: str, shape: int | tuple[int, ...] = 1, lower=-np.inf, upper=np.inf,
                  scale=1.0, names=None) -> ca.SX:
        """Decision variables ``name`` of ``shape`` within [``lower``, ``upper``]; their symbol (a column, or a
        matrix for a 2-d shape)."""
        self._check_new(name, self._variables)
        shape = (shape,) if isinstance(shape, int) else tuple(shape)
        block = Block(name, self._next(self._variables), shape)
        bounded = BoundedBlock(name, block.start, shape, block.flat(lower), block.flat(upper), block.flat(scale),
                               _per_entry(names, block.size))
        symbol = ca.SX.sym(name, block.size)
        self._variables.append((bounded, symbol))
        return ca.reshape(symbol, *shape) if len(shape) == 2 else symbol

    def parameters(self, name: str, shape: int | tuple[int, ...] = 1) -> ca.SX:
        """Parameters ``name`` of ``shape``, set at each solve; their symbol."""
        self._check_new(name, self._parameters)
        shape = (shape,) if isinstance(shape, int) else tuple(shape)
        symbol = ca.SX.sym(name, *shape) if len(shape) == 2 else ca.SX.sym(name, shape[0])
        self._parameters.append((Block(name, self._next(self._parameters), shape), symbol))
        return symbol

    def lifted(self, name: str, expression) -> ca.SX:
        """A symbol standing for ``expression`` (of the variables and parameters; any shape) in the
        expressions that follow: the NLP is the same, and the Hessian of its Lagrangian is formed through
        these quantities (``solve.lifted_hessian``) and the rows' Jacobian through them too
        (``solve.lifted_jacobian``): worth it where many rows share few of them each."""
        expression = ca.SX(expression)
        symbol = ca.SX.sym(name, *expression.shape)
        self._lifted.append((ca.vec(symbol), ca.vec(expression)))
        return symbol

    def constraints(self, name: str, expression, lower, upper, scale=1.0, names=None) -> None:
        """Rows ``lower <= expression <= upper`` named ``name`` (``expression`` a column); ``scale`` is the
        size a row's distance from its bound is judged against; ``names`` the (lower, upper) bound names,
        one pair for every row or a pair per row (None: the rows' bounds are never reported)."""
        self._check_new(name, self._rows)
        expression = ca.vec(ca.SX(expression))
        size = expression.shape[0]
        block = Block(name, self._next(self._rows), (size,))
        self._rows.append((BoundedBlock(name, block.start, (size,), block.flat(lower), block.flat(upper),
                                        block.flat(scale), _per_entry(names, size)), expression))

    def build(self, objective) -> NLPLayout:
        x = ca.vertcat(*(symbol for _, symbol in self._variables))
        p = ca.vertcat(*(ca.vec(symbol) for _, symbol in self._parameters))
        f, g = ca.SX(objective), ca.vertcat(*(expression for _, expression in self._rows))
        hessian = jacobian = None
        if self._lifted:
            lifted, values = (ca.vertcat(*side) for side in zip(*self._lifted, strict=True))
            hessian = lifted_hessian(x, p, lifted, values, f, g)
            jacobian = lifted_jacobian(x, p, self._lifted, g)
            f, g = ca.substitute([f, g], [lifted], [values])
        return NLPLayout(
            x=x, p=p, f=f, g=g,
            variables={block.name: block for block, _ in self._variables},
            parameters={block.name: block for block, _ in self._parameters},
            rows={block.name: block for block, _ in self._rows}, hessian=hessian, jacobian=jacobian)


@dataclass(frozen=True)
class NLPLayout:
    """The NLP in CasADi form with its named blocks (``variables``, ``parameters``, ``rows``)."""

    x: ca.SX
    p: ca.SX
    f: ca.SX
    g: ca.SX
    variables: Mapping[str, BoundedBlock]
    parameters: Mapping[str, Block]
    rows: Mapping[str, BoundedBlock]
    #: The Hessian of the Lagrangian through the lifted quantities (IPOPT's ``hess_lag``), or None
    #: (CasADi forms it): ``NLPBuilder.lifted``.
    hessian: ca.Function | None = None
    #: The rows and their Jacobian through the lifted quantities (IPOPT's ``jac_g``), or None (CasADi forms it).
    jacobian: ca.Function | None = None

    def vector(self, values: Mapping[str, object]) -> np.ndarray:
        """The decision vector from a value for every variable block, by name."""
        return _assemble(self.variables, values, self.x.shape[0], "variable")

    def parameter_vector(self, values: Mapping[str, object]) -> np.ndarray:
        """The parameter vector from a value for every parameter block, by name."""
        return _assemble(self.parameters, values, self.p.shape[0], "parameter")

    def bounds(self) -> Bounds:
        """A fresh copy of every block's declared bounds, to adjust for one solve."""
        def stacked(blocks: Mapping[str, BoundedBlock], side: str) -> np.ndarray:
            return np.concatenate([getattr(b, side) for b in blocks.values()]) if blocks else np.empty(0)
        return Bounds(self, stacked(self.variables, "lower"), stacked(self.variables, "upper"),
                      stacked(self.rows, "lower"), stacked(self.rows, "upper"))

    def row_scales(self) -> np.ndarray:
        return np.concatenate([b.scale for b in self.rows.values()]) if self.rows else np.empty(0)


def _assemble(blocks: Mapping[str, Block], values: Mapping[str, object], size: int, kind: str) -> np.ndarray:
    missing, unknown = set(blocks) - set(values), set(values) - set(blocks)
    if missing or unknown:
        raise ValueError(f"{kind} values: missing {sorted(missing)}, unknown {sorted(unknown)}")
    vector = np.empty(size)
    for name, block in blocks.items():
        vector[block.slice] = block.flat(values[name])
    return vector


@dataclass
class Bounds:
    """The bounds of one solve, set by block name (``rows`` selects entries within a block)."""

    layout: NLPLayout
    lbx: np.ndarray
    ubx: np.ndarray
    lbg: np.ndarray
    ubg: np.ndarray

    def set_rows(self, name: str, lower, upper, rows: slice | Sequence[int] = slice(None)) -> Bounds:
        block = self.layout.rows[name]
        indices = np.arange(block.start, block.start + block.size)[rows]
        self.lbg[indices], self.ubg[indices] = lower, upper
        return self

    def free_rows(self, name: str, rows: slice | Sequence[int] = slice(None)) -> Bounds:
        """The rows constrain nothing in this solve."""
        return self.set_rows(name, -np.inf, np.inf, rows)

    def set_variables(self, name: str, lower, upper, entries: slice | Sequence[int] = slice(None)) -> Bounds:
        block = self.layout.variables[name]
        indices = np.arange(block.start, block.start + block.size)[entries]
        self.lbx[indices], self.ubx[indices] = lower, upper
        return self

    def fix(self, name: str, value, entries: slice | Sequence[int] = slice(None)) -> Bounds:
        """Variables held at ``value`` in this solve."""
        return self.set_variables(name, value, value, entries)

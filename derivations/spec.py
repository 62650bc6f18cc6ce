"""The record a derivation module hands to the printer."""
from __future__ import annotations

from dataclasses import dataclass

import sympy as sp


@dataclass(frozen=True)
class Derived:
    """One generated function: named input groups of symbols -> named output groups of expressions."""

    name: str
    doc: str
    inputs: tuple[tuple[str, tuple[sp.Symbol, ...]], ...]
    outputs: tuple[tuple[str, tuple[sp.Expr, ...]], ...]

    def input_symbols(self) -> list[sp.Symbol]:
        return [s for _, group in self.inputs for s in group]


def symbol_group(name: str, size: int) -> tuple[sp.Symbol, ...]:
    """Real symbols ``name_0 .. name_{size-1}``: the printer unpacks them from ``name[k]``."""
    return tuple(sp.Symbol(f"{name}_{k}", real=True) for k in range(size))

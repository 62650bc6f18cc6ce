"""Which named bounds a solution sits on, decided in one place for every NLP.

An entry (a variable or a constraint row) is on its bound when it lies within ``ON_BOUND`` of the
entry's scale from it, or when IPOPT's multiplier on that bound exceeds ``MULTIPLIER_FLOOR`` (an
interior point stops a hair inside a bound that still binds; the multiplier of an inactive bound
decays to about 1e-10). Only bounds the NLP names are reported (``NLPBuilder``'s ``names``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.solve.layout import Bounds, NLPLayout

ON_BOUND = 1e-6
MULTIPLIER_FLOOR = 1e-6


@dataclass(frozen=True)
class ActiveBound:
    """A named bound a solution sits on: ``name`` (as the problem file or the report names it),
    ``side`` of the named quantity it limits (``lower`` or ``upper``), the bound's ``limit`` and the
    solution's most binding ``value`` (both in the NLP's own units), the block it was found in and the
    entries of that block on it."""

    name: str
    side: str
    limit: float
    value: float
    block: str
    entries: tuple[int, ...]

    def __str__(self) -> str:
        return f"{self.name} {'>=' if self.side == 'lower' else '<='} {self.limit:g}"


def on_bounds(values: np.ndarray, lower: np.ndarray, upper: np.ndarray, multipliers: np.ndarray,
              scale: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per entry, whether it sits on its lower bound and whether on its upper one (the module docstring's rule;
    ``scale``: the entries' scales; CasADi's multiplier signs: negative on a lower bound, positive on an upper)."""
    tolerance = ON_BOUND * scale
    low = np.isfinite(lower) & ((values - lower <= tolerance) | (multipliers < -MULTIPLIER_FLOOR))
    high = np.isfinite(upper) & ((upper - values <= tolerance) | (multipliers > MULTIPLIER_FLOOR))
    return low, high


def active_bounds(layout: NLPLayout, bounds: Bounds, x: np.ndarray, g: np.ndarray, lam_x: np.ndarray,
                  lam_g: np.ndarray) -> tuple[ActiveBound, ...]:
    """Every named bound the point (x, g) with multipliers (lam_x, lam_g) sits on, in block order; a name
    is reported once, with the entries of the first block it is found on."""
    on: dict[tuple[str, str], list[tuple[float, float, str, int, bool]]] = {}
    for blocks, values, lower, upper, multipliers in ((layout.variables, x, bounds.lbx, bounds.ubx, lam_x),
                                                      (layout.rows, g, bounds.lbg, bounds.ubg, lam_g)):
        for block in blocks.values():
            span = block.slice
            on_low, on_high = on_bounds(values[span], lower[span], upper[span], multipliers[span], block.scale)
            for entry, (low_name, high_name) in enumerate(block.names):
                k = block.start + entry
                if low_name and on_low[entry]:
                    on.setdefault(low_name, []).append((lower[k], values[k], block.name, entry, True))
                if high_name and on_high[entry]:
                    on.setdefault(high_name, []).append((upper[k], values[k], block.name, entry, False))
    found = []
    for (name, side), hits in on.items():
        first = [hit for hit in hits if hit[2] == hits[0][2]]
        at = [hit[1] for hit in first]
        # the most binding value: the least on a row's lower bound, the greatest on its upper (the row's
        # side, which may be the named quantity's other one: a lower bound on rho' is an upper one on the ratio)
        value = min(at) if first[0][4] else max(at)
        found.append(ActiveBound(name, side, float(first[0][0]), float(value), first[0][2],
                                 tuple(hit[3] for hit in first)))
    return tuple(found)

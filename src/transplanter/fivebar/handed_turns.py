"""Which exchange turns a lane hands from one refinement to its next start (``DesignSolver``).

An exchange turn's rows hold a condition the whole turn must meet anyway, so offering a turn changes no
solution; it spares the next start the round that would add it again. The NLP has room for ``capacity`` turns
and a start needs room for its own rounds, so at most half of it is handed on: first the turns whose rows the
design sits on (``solve.active``'s rule; the largest multiplier first), then the latest added of the others, in
increasing order. A design held at more turns than that keeps its binding ones: with the latest added alone, a
design held at 9-10 separate turns (the bundled example with a 48 deg pressure limit) was offered a different 8
at every start, the dropped turns came back, and no later start could take an earlier refinement's optimum
(``reached_optima``): 76 solves and 2,946 IPOPT iterations against 43 and 2,108 with the binding turns kept, the
same design picked (``bench/bench_handed_turns.py``).
"""
from __future__ import annotations

import numpy as np

from transplanter.solve.active import on_bounds
from transplanter.solve.ipopt import Solution


def handed_turns(solved: Solution, blocks: tuple[str, ...], first_slot: int, added: np.ndarray,
                 keep: int) -> np.ndarray:
    """At most ``keep`` of the exchange turns ``added`` (rad, in slot order from row ``first_slot`` of each grid
    block ``blocks``) for the next start (module docstring), in increasing order."""
    slots = slice(first_slot, first_slot + len(added))
    binding, strength = np.zeros(len(added), bool), np.zeros(len(added))
    for name in blocks:
        block = solved.layout.rows[name]
        rows = np.arange(block.start, block.start + block.size)[slots]
        low, high = on_bounds(solved.g[rows], solved.bounds.lbg[rows], solved.bounds.ubg[rows],
                              solved.lam_g[rows], block.scale[slots])
        binding |= low | high
        strength = np.fmax(strength, np.where(low | high, np.abs(solved.lam_g[rows]), 0.0))
    order = [*(i for i in np.argsort(-strength, kind="stable") if binding[i]),
             *(i for i in range(len(added) - 1, -1, -1) if not binding[i])]
    return np.sort(added[order[:keep]])

"""The exchange method for conditions that must hold over a whole interval (a carrier turn): solve
with the condition imposed on a grid, check it on a much finer one, add the worst points to the grid,
and solve again, until the fine check holds or the rounds run out."""
from __future__ import annotations

from collections.abc import Callable
from typing import TypeVar

import numpy as np

Solved = TypeVar("Solved")


def exchange(solve: Callable[[np.ndarray, Solved | None], Solved], worst_points: Callable[[Solved], np.ndarray],
             points: np.ndarray, rounds: int, warm: Solved | None = None,
             first: Solved | None = None) -> tuple[Solved, np.ndarray]:
    """``solve(points, previous)`` from ``warm``, then again with ``worst_points(solution)`` added to
    ``points``, until it finds none (or after ``rounds`` solves); the last solution and the points held.
    ``first``: the first solve's solution, where the caller has it already."""
    solution = warm
    for round_ in range(rounds):
        solution = first if round_ == 0 and first is not None else solve(points, solution)
        worst = worst_points(solution)
        if not worst.size:
            break
        points = np.r_[points, worst]
    assert solution is not None
    return solution, points


def periodic_peaks(shortfall: np.ndarray, floor: float = 1e-9) -> np.ndarray:
    """Indices of the local maxima of a periodic sampled shortfall where it exceeds ``floor`` (rounding)."""
    peak = (shortfall >= np.roll(shortfall, 1)) & (shortfall > np.roll(shortfall, -1))
    return np.flatnonzero(peak & (shortfall > floor))

"""The non-dominated points of a set, each objective minimised or maximised."""
from __future__ import annotations

import numpy as np


def pareto_front(points: np.ndarray, goals: list[str]) -> np.ndarray:
    """Indices of the rows of ``points`` (n x k, finite rows only) that no other row dominates: no worse in
    every objective and better in one; ``goals`` gives "min" or "max" per column."""
    signs = np.array([1.0 if goal == "min" else -1.0 for goal in goals])
    finite = np.flatnonzero(np.isfinite(points).all(axis=1))
    costs = points[finite] * signs
    no_worse = (costs[:, None, :] <= costs[None, :, :]).all(axis=2)
    better = (costs[:, None, :] < costs[None, :, :]).any(axis=2)
    dominated = (no_worse & better).any(axis=0)
    return finite[~dominated]

"""Refinements a lane's solver has finished, recognised when a later start reaches the same optimum.

A refinement is a chain of solves (exchange rounds, then the max-min of the transmission angle alone) whose
every solve after the first depends only on that first solve's optimum, the exchange turns it was offered
and the start's assembly branch. A later start whose first solve is offered the same turns with the same
branch and ends at the same optimum (x within ``SAME_OPTIMUM`` in the NLP's units, where lengths are
fractions of the problem's own unit) would repeat that chain: its outcome, design or failure, and the
exchange turns it leaves are taken from the first. On the bundled example starts that reach one optimum
agree to 5e-11 after their first solve, the tolerance is 1e-7, far inside the 1e-4 of the reach at which
two designs count as one mechanism (``alternatives.MERGE_TOLERANCE``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: Largest difference of two first-solve optima (NLP units: lengths over the problem's unit, radians, t)
#: that are one optimum.
SAME_OPTIMUM = 1e-7


@dataclass(frozen=True)
class ReachedOptimum:
    """One finished refinement: what its first solve was offered (``turns``, rad; ``branch``), where it
    ended (``x``), the refinement's ``outcome`` (a design or the error it ended with) and the exchange
    turns it left (``turns_after``)."""

    turns: np.ndarray
    branch: float
    x: np.ndarray
    outcome: object
    turns_after: np.ndarray

    def repeats(self, turns: np.ndarray, branch: float, x: np.ndarray) -> bool:
        """Whether a first solve offered ``turns`` with ``branch`` that ended at ``x`` is this one's."""
        return (branch == self.branch and turns.shape == self.turns.shape and bool(np.all(turns == self.turns))
                and x.shape == self.x.shape and float(np.abs(x - self.x).max()) <= SAME_OPTIMUM)


def reached(optima: tuple[ReachedOptimum, ...], turns: np.ndarray, branch: float,
            x: np.ndarray) -> ReachedOptimum | None:
    """The finished refinement of ``optima`` that a first solve (offered ``turns`` with ``branch``, ended at
    ``x``) repeats, or None."""
    return next((optimum for optimum in optima if optimum.repeats(turns, branch, x)), None)

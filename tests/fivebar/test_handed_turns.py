"""The exchange turns a lane hands to its next start: those the design sits on first (the largest multiplier
first), then the latest added, at most ``keep``, in increasing order; rows of the grid's fixed points and of
empty slots never count. Checked on a solution whose binding rows are set by hand."""
import casadi as ca
import numpy as np

from transplanter.fivebar.handed_turns import handed_turns
from transplanter.solve import NLPBuilder
from transplanter.solve.ipopt import Solution

FIXED, SLOTS = 2, 6
#: Exchange turns in slots 0-4 (slot 5 empty), rad.
ADDED = np.array([0.5, 0.1, 0.9, 0.3, 0.7])


def _solution() -> Solution:
    """Two grid blocks, ``low`` (rows >= 0) and ``high`` (rows <= 0), each a row per fixed point and slot. On a
    bound: both fixed points (to be ignored), slot 1 in ``low`` (multiplier -2), slot 3 in ``high`` (+5, a hair
    inside it) and the empty slot 5 (ignored); slot 4 sits 1e-3 above its bound with a decayed multiplier: free."""
    nlp = NLPBuilder()
    x = nlp.variables("x", 1)
    nlp.constraints("low", ca.repmat(x, FIXED + SLOTS, 1), 0.0, np.inf)
    nlp.constraints("high", ca.repmat(x, FIXED + SLOTS, 1), -np.inf, 0.0)
    layout = nlp.build(x)
    low, high = np.full(FIXED + SLOTS, 0.4), np.full(FIXED + SLOTS, -0.4)
    lam_low, lam_high = np.zeros(FIXED + SLOTS), np.zeros(FIXED + SLOTS)
    low[[0, 1, FIXED + 1, FIXED + 5]], lam_low[[0, FIXED + 1]] = 0.0, [-9.0, -2.0]
    high[[1, FIXED + 3]], lam_high[[1, FIXED + 3]] = [0.0, -1e-9], [9.0, 5.0]
    low[FIXED + 4], lam_low[FIXED + 4] = 1e-3, -1e-10
    return Solution(layout, layout.bounds(), np.zeros(1), np.r_[low, high], np.zeros(1), np.r_[lam_low, lam_high],
                    0.0, 1, "Solve_Succeeded")


def _handed(keep: int) -> list[float]:
    return handed_turns(_solution(), ("low", "high"), FIXED, ADDED, keep).tolist()


def test_the_binding_turns_go_first_the_largest_multiplier_first():
    assert _handed(1) == [0.3]                   # slot 3 (5) before slot 1 (2)
    assert _handed(2) == [0.1, 0.3]              # the latest two added would be slots 3 and 4: 0.3 and 0.7


def test_the_room_left_is_filled_with_the_latest_added_of_the_others():
    assert _handed(3) == [0.1, 0.3, 0.7]         # slot 4, the latest free one
    assert _handed(4) == [0.1, 0.3, 0.7, 0.9]    # then slot 2; slot 0 (0.5) is the oldest
    assert _handed(9) == sorted(ADDED.tolist())  # room for all: every turn added, none of the empty slot

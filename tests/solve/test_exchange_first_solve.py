"""The exchange method continued from a first solve the caller has already done (``exchange``'s ``first``):
the same rounds and result as when it solves that first round itself, one solve fewer."""
import numpy as np

from transplanter.solve import exchange, periodic_peaks


def test_a_given_first_solve_replaces_the_first_round_and_nothing_else():
    def f(s):
        return 1 + 0.3 * np.cos(3 * (s - 0.4)) + 0.1 * np.sin(s)

    fine = np.linspace(0, 2 * np.pi, 20000, endpoint=False)
    calls: list[int] = []

    def solve(points, previous):
        calls.append(len(points))
        return float(f(points).min())

    def worst(t):
        return fine[periodic_peaks(t - f(fine))]

    coarse = np.linspace(0, 2 * np.pi, 5, endpoint=False)
    whole, whole_points = exchange(solve, worst, coarse, rounds=4)
    solved_rounds = list(calls)
    calls.clear()
    given, given_points = exchange(solve, worst, coarse, rounds=4, first=float(f(coarse).min()))
    assert given == whole and np.array_equal(given_points, whole_points)
    assert calls == solved_rounds[1:] and len(solved_rounds) > 1

"""The re-solve with a return point moved to another pass of P (``DesignSolver.restroke``) starts from the design's
multipliers, which travel with the design as plain arrays: a design that crossed a process boundary (a result of
the forked lane) restrokes exactly as it does where it was solved."""
from __future__ import annotations

import pickle

from transplanter.fivebar.alternatives import Alternative, assess
from transplanter.fivebar.design_solver import DesignSolver
from transplanter.fivebar.report import alternative_json
from transplanter.fivebar.return_passes import other_passes
from transplanter.solve import Solver


def test_a_restroke_starts_from_the_multipliers_the_design_carries_here_or_after_pickling(
        example_problem, example_result, monkeypatch):
    picked = example_result.alternatives[0]
    first = picked.starts[0]
    start = example_result.region.feasible[first]
    point, turn = other_passes(example_problem, picked.design)[0]
    arrived = pickle.loads(pickle.dumps(picked.design))      # as a result of the forked lane arrives
    assert arrived.solved is None and arrived.multipliers is not None
    continued = []
    solve = Solver.solve

    def recorded(self, *arguments, continues=None, **options):
        continued.append(continues)
        return solve(self, *arguments, continues=continues, **options)

    monkeypatch.setattr(Solver, "solve", recorded)
    built = DesignSolver(example_problem)
    judged = []
    for design in (picked.design, arrived):
        continued.clear()
        moved = built.twin().restroke(start, design, point, turn)
        assert continued[0] is design.multipliers and all(previous is not None for previous in continued)
        judged.append(assess(example_problem, moved, first))       # its own whole-turn evaluation
    assert all(isinstance(alternative, Alternative) for alternative in judged)
    assert alternative_json(judged[0], 1, example_problem.poses[0]) == alternative_json(judged[1], 1,
                                                                                        example_problem.poses[0])

"""The return-stroke re-solves of the alternatives, two at a time in the refinement lanes: the same designs,
numbers and solver state left behind whether lane 1 runs in a side process or after lane 0 here."""
from __future__ import annotations

import os

import numpy as np

from transplanter import side_process
from transplanter.fivebar import alternatives
from transplanter.fivebar.design_solver import DesignSolver
from transplanter.fivebar.report import alternative_json
from transplanter.fivebar.return_passes import other_passes


def test_restrokes_reach_the_same_designs_in_a_side_process_or_in_turn(example_problem, example_result, monkeypatch,
                                                                       tmp_path):
    """From the picked design, every other pass of its return points re-solved (each judged by ``assess``'s
    whole-turn evaluation): the report's numbers agree to the last digit either way."""
    picked, candidates = example_result.alternatives[0], list(example_result.region.feasible)
    moves = other_passes(example_problem, picked.design)
    assert len(moves) >= 2, "a second lane to run"
    solvers = tmp_path / "solved_by"
    restroke = DesignSolver.restroke

    def recorded(self, *arguments):
        with solvers.open("a") as file:
            file.write(f"{os.getpid()}\n")
        return restroke(self, *arguments)

    monkeypatch.setattr(DesignSolver, "restroke", recorded)
    built = DesignSolver(example_problem)

    def restroked(forks: bool):
        monkeypatch.setattr(side_process, "usable_cores", lambda: 2 if forks else 1)
        solvers.unlink(missing_ok=True)
        solver = built.twin()
        (best,) = alternatives._other_strokes(example_problem, solver, candidates, [picked])
        processes = set(solvers.read_text().split())
        return alternative_json(best, 1, example_problem.poses[0]), best.restroke, solver.exchange_turns, processes

    beside, in_turn = restroked(True), restroked(False)
    assert len(beside[3]) == 2 and in_turn[3] == {str(os.getpid())}
    assert beside[0] == in_turn[0] and beside[1] == in_turn[1]
    np.testing.assert_array_equal(beside[2], in_turn[2])

"""The lanes follow the cores this process may use: on one core lane 1 runs after lane 0 here, on a solver of its
own, with the outcome of the forked lane on two."""
from __future__ import annotations

import os

from tests.fivebar.test_refinement_lanes import Solver, refine
from transplanter import side_process
from transplanter.fivebar.lanes import refine_in_lanes


def _lanes(cores: int, monkeypatch) -> tuple[list, dict]:
    monkeypatch.setattr(side_process, "usable_cores", lambda: cores)
    built, reported = [], {}

    def new_solver():
        built.append(Solver())
        return built[-1]

    refine_in_lanes(5, refine, Solver(), new_solver, lambda index, outcome, seconds: reported.update({index: outcome}))
    return built, reported


def test_on_one_core_lane_1_runs_here_with_the_outcome_of_two(monkeypatch):
    built_one, one = _lanes(1, monkeypatch)
    built_two, two = _lanes(2, monkeypatch)
    assert len(built_one) == 1 and {pid for *_, pid in one.values()} == {os.getpid()}
    assert built_two == [] and {two[k][2] for k in (1, 3)} != {os.getpid()}
    assert {k: outcome[:2] for k, outcome in one.items()} == {k: outcome[:2] for k, outcome in two.items()} == {
        0: (0, ()), 2: (2, (0,)), 4: (4, (0, 2)), 1: (1, ()), 3: (3, (1,))}

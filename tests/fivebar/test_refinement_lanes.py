"""The refinement lanes: fixed candidates per lane, each lane's solver fresh when it starts, the same
outcome forked or not, results reported in the caller's thread, a lane's defect raised."""
import os
import threading

import pytest

from transplanter import side_process
from transplanter.fivebar import lanes
from transplanter.fivebar.lanes import refine_in_lanes


class Solver:
    """Stands in for a DesignSolver: state that each refinement changes, as the exchange turns do."""

    def __init__(self):
        self.refined = []


def refine(solver, index):
    """The outcome records which candidates this solver refined before, and in which process."""
    outcome = (index, tuple(solver.refined), os.getpid())
    solver.refined.append(index)
    return outcome


def run(count, forks: bool, monkeypatch):
    if forks:       # as on a machine that gives this process two cores, whatever runs the test
        monkeypatch.setattr(side_process, "usable_cores", lambda: 2)
    else:
        monkeypatch.setattr(side_process, "FORKS", False)
    solver, built, reported = Solver(), [], []

    def new_solver():
        built.append(Solver())
        return built[-1]

    def finished(index, outcome, seconds):
        reported.append((index, outcome, seconds, threading.current_thread() is threading.main_thread()))

    refine_in_lanes(count, refine, solver, new_solver, finished)
    return solver, built, reported


@pytest.mark.parametrize("forks", [True, False])
def test_lane_k_refines_candidates_k_k_plus_2_on_a_solver_fresh_when_the_lane_starts(forks, monkeypatch):
    solver, built, reported = run(7, forks, monkeypatch)
    assert sorted(index for index, *_ in reported) == list(range(7))
    assert all(in_main and seconds >= 0 for *_, seconds, in_main in reported)
    before = {index: earlier for index, (_, earlier, _), *_ in reported}
    assert before == {0: (), 2: (0,), 4: (0, 2), 6: (0, 2, 4), 1: (), 3: (1,), 5: (1, 3)}
    assert solver.refined == [0, 2, 4, 6]           # lane 0's solver, left with lane 0's state
    pids = {index: pid for index, (_, _, pid), *_ in reported}
    assert {pids[k] for k in (0, 2, 4, 6)} == {os.getpid()}
    if forks:
        assert built == [] and {pids[k] for k in (1, 3, 5)} != {os.getpid()}
    else:
        assert len(built) == 1 and {pids[k] for k in (1, 3, 5)} == {os.getpid()}


def test_within_lanes_here_lane_1_runs_in_this_process_with_the_forked_outcome(monkeypatch):
    """A study with a worker per core: no fork, each candidate refined from the same solver state."""
    forked = run(5, True, monkeypatch)[2]
    with lanes.lanes_here():
        solver, built, reported = run(5, True, monkeypatch)
    assert len(built) == 1 and {outcome[2] for _, outcome, *_ in reported} == {os.getpid()}
    assert sorted((index, outcome[:2]) for index, outcome, *_ in reported) == \
        sorted((index, outcome[:2]) for index, outcome, *_ in forked)
    assert side_process._may_fork.get()        # forking again after the block


def test_one_candidate_needs_no_second_lane(monkeypatch):
    solver, built, reported = run(1, True, monkeypatch)
    assert [index for index, *_ in reported] == [0] and built == [] and solver.refined == [0]


def test_a_defect_in_the_forked_lane_is_raised_in_the_caller(monkeypatch):
    def faulty(solver, index):
        if index == 3:
            raise ValueError("lane 1 broke on candidate 3")
        return index

    with pytest.raises(ValueError, match="lane 1 broke on candidate 3"):
        refine_in_lanes(5, faulty, Solver(), Solver, lambda *_: None)


def test_a_system_that_refuses_the_process_runs_the_lanes_here(monkeypatch):
    """A sandbox without semaphores or fork: the pool's OSError leaves lane 1 to this process, same outcome."""
    def refused(*args, **kwargs):
        raise OSError(38, "Function not implemented")

    monkeypatch.setattr(side_process, "ProcessPoolExecutor", refused)
    solver, built, reported = run(5, True, monkeypatch)
    assert len(built) == 1 and {outcome[2] for _, outcome, *_ in reported} == {os.getpid()}
    assert {index: earlier for index, (_, earlier, _), *_ in reported} == {0: (), 2: (0,), 4: (0, 2), 1: (), 3: (1,)}


def test_an_interrupt_in_the_caller_stops_the_forked_lane_at_once():
    """Ctrl-C reaching the caller between candidates: the forked lane's process is ended, not waited for (its
    candidates take 2 s each here, the interrupt comes after the first of the caller's own)."""
    import time

    def slow(solver, index):
        if index % 2:
            time.sleep(2.0)
        return index

    def finished(index, outcome, seconds):
        raise KeyboardInterrupt

    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        refine_in_lanes(8, slow, Solver(), Solver, finished)
    assert time.perf_counter() - start < 1.0

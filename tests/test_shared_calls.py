"""Calls shared between a side process and this one: results in order wherever each ran, each call run once, the
side process taking the first calls and this process the last once its own work is done, and every failure raised
here."""
from __future__ import annotations

import os
import time

import pytest

from transplanter import side_process
from transplanter.errors import TransplanterError
from transplanter.shared_calls import share_calls, shared_map


@pytest.fixture
def two_cores(monkeypatch):
    """As on a machine that gives this process two cores, whatever runs the test."""
    monkeypatch.setattr(side_process, "usable_cores", lambda: 2)


def _where(index: int, first_takes: float = 0.0) -> tuple[int, int]:
    """The call's index and the process it ran in; the first call takes ``first_takes`` s."""
    if index == 0:
        time.sleep(first_takes)
    return index, os.getpid()


@pytest.mark.skipif(not side_process.FORKS, reason="a side process is forked on Linux only")
def test_the_side_process_takes_the_first_calls_and_this_one_the_last(two_cores):
    """This process's own work (0.5 s) outlasts the side process's start, which claims the first call (1 s); this
    process then takes the rest, the last first."""
    results, mine = share_calls(lambda index: _where(index, first_takes=1.0), [(k,) for k in range(6)],
                                lambda: time.sleep(0.5) or "here")
    assert mine == "here" and [index for index, _ in results] == list(range(6))
    side = results[0][1]
    assert side != os.getpid() and results[-1][1] == os.getpid()
    assert {pid for _, pid in results} == {side, os.getpid()}


@pytest.mark.skipif(not side_process.FORKS, reason="a side process is forked on Linux only")
def test_two_calls_take_one_process_each(two_cores):
    """Neither process holds a call it has not started: with two calls (0.5 s each) and 0.1 s of its own work here,
    the side process takes the first and this one the second, not both queued for the side. (The side process has
    until this one has made the second call to start, even on a loaded machine.)"""
    results, _ = share_calls(lambda index: (time.sleep(0.5), index, os.getpid())[1:], [(0,), (1,)],
                             lambda: time.sleep(0.1))
    assert results[0][0] == 0 and results[1] == (1, os.getpid()) and results[0][1] != os.getpid()


@pytest.mark.skipif(not side_process.FORKS, reason="a side process is forked on Linux only")
def test_every_call_runs_once(two_cores, tmp_path):
    """Forty calls of uneven length, each writing its index to a log as it runs: each is there once, and both
    processes took some."""
    log = tmp_path / "calls.log"

    def work(index: int) -> tuple[int, int]:
        time.sleep(0.02 * (index % 5))
        with log.open("a") as file:
            file.write(f"{index}\n")
        return index, os.getpid()

    results = shared_map(work, [(k,) for k in range(40)])
    assert [index for index, _ in results] == list(range(40))
    assert sorted(map(int, log.read_text().split())) == list(range(40))
    assert len({pid for _, pid in results}) == 2


def test_in_turn_where_no_side_process_may_run(monkeypatch):
    monkeypatch.setattr(side_process, "FORKS", False)
    order = []
    results, mine = share_calls(lambda index: order.append(index) or index, [(k,) for k in range(3)],
                                lambda: order.append("here") or "here")
    assert results == [0, 1, 2] and mine == "here" and order == [0, 1, 2, "here"]


@pytest.mark.parametrize("forks", [True, False], ids=["beside", "here"])
def test_a_call_that_fails_is_raised_here(monkeypatch, two_cores, forks):
    monkeypatch.setattr(side_process, "FORKS", forks and side_process.FORKS)

    def work(index: int) -> int:
        if index == 0:
            raise TransplanterError("call 0 failed")
        return index

    with pytest.raises(TransplanterError, match="call 0 failed"):
        share_calls(work, [(k,) for k in range(3)], lambda: None)


def test_this_process_failing_stops_the_side_process(two_cores):
    def here():
        raise TransplanterError("here failed")

    with pytest.raises(TransplanterError, match="here failed"):
        share_calls(lambda index: time.sleep(60), [(k,) for k in range(2)], here)


def test_a_single_call_with_nothing_else_to_do_is_made_here(two_cores):
    assert shared_map(lambda index: (index, os.getpid()), [(0,)]) == [(0, os.getpid())]

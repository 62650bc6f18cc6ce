"""Calls shared between this process and a side process, so both cores end together.

``share_calls(work, calls, here)``: a side process (``side_process``) takes ``work(*call)`` for the calls in order
while this process runs ``here()``; then this process takes the calls the side process has not reached, the last
first, until none is left. Each call is claimed from one end or the other of a range both processes share, so no
call runs twice and none waits while the other process has one to spare. Which process does a call follows the
machine's speed, so ``work`` must give the same result wherever it runs (the command line's figures: each saved to
its own file).
"""
from __future__ import annotations

import multiprocessing
from collections.abc import Callable, Sequence
from functools import partial
from typing import TypeVar

from transplanter.side_process import may_fork, outcome, start_side_process

Call = TypeVar("Call")
Here = TypeVar("Here")


class _Ends:
    """The calls not yet claimed, from ``[0]`` up to ``[1]``, in memory both processes share (made before the fork):
    the side process claims from the front, this one from the back."""

    def __init__(self, count: int):
        self._range = multiprocessing.get_context("fork").Array("i", [0, count])

    def claim(self, front: bool) -> int | None:
        """The first call left (``front``) or the last, claimed; None where none is left."""
        with self._range.get_lock():
            first, stop = int(self._range[0]), int(self._range[1])
            if first >= stop:
                return None
            if front:
                self._range[0] = first + 1
                return first
            self._range[1] = stop - 1
            return stop - 1


def share_calls(work: Callable[..., Call], calls: Sequence[tuple], here: Callable[[], Here]
                ) -> tuple[list[Call], Here]:
    """``work(*call)`` for each of ``calls`` and ``here()``, on two cores where the machine gives a second (module
    docstring), else in turn here; the calls' results in their order, and ``here()``'s. An exception of either is
    raised here (the side process then stopped)."""
    ends = _shared_ends(len(calls))
    started = start_side_process(partial(_from_the_front, work, calls, ends), [()]) if ends else None
    if ends is None or started is None:
        return [work(*call) for call in calls], here()
    side, (future,) = started
    try:
        mine = here()
        taken: dict[int, Call] = {}
        while (index := ends.claim(front=False)) is not None:
            taken[index] = work(*calls[index])
        taken.update(outcome(future))
    except BaseException:
        side.stop()
        raise
    side.close()
    return [taken[index] for index in range(len(calls))], mine


def _shared_ends(count: int) -> _Ends | None:
    """The ends of ``count`` calls where a side process may take some (``side_process.may_fork``); None where none
    may or the system gives no shared memory (a sandbox)."""
    if not count or not may_fork():
        return None
    try:
        return _Ends(count)
    except OSError:
        return None


def _from_the_front(work: Callable[..., Call], calls: Sequence[tuple], ends: _Ends) -> dict[int, Call]:
    """In the side process: the calls claimed from the front, by index, until none is left."""
    done = {}
    while (index := ends.claim(front=True)) is not None:
        done[index] = work(*calls[index])
    return done


def shared_map(work: Callable[..., Call], calls: Sequence[tuple]) -> list[Call]:
    """``share_calls`` with nothing else to do here: the calls' results in their order (one call is made here: a
    side process would only add its start)."""
    if len(calls) < 2:
        return [work(*call) for call in calls]
    return share_calls(work, calls, _nothing)[0]


def _nothing() -> None:
    return None

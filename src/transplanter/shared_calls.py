"""Calls shared between this process and a side process, so both cores end together.

``share_calls(work, calls, here)``: a side process (``side_process``) takes ``work(*call)`` for the calls in order
while this process runs ``here()``; then this process takes the calls the side process has not reached, the last
first, until none is left. Which process does a call follows the machine's speed, so ``work`` must give the same
result wherever it runs (the command line's figures: each saved to its own file).
"""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TypeVar

from transplanter.side_process import outcome, start_side_process

Call = TypeVar("Call")
Here = TypeVar("Here")


def share_calls(work: Callable[..., Call], calls: Sequence[tuple], here: Callable[[], Here]
                ) -> tuple[list[Call], Here]:
    """``work(*call)`` for each of ``calls`` and ``here()``, on two cores where the machine gives a second (module
    docstring), else in turn here; the calls' results in their order, and ``here()``'s. An exception of either is
    raised here (the side process then stopped)."""
    started = start_side_process(work, calls)
    if started is None:
        return [work(*call) for call in calls], here()
    side, futures = started
    try:
        mine = here()
        taken = {}
        for index in reversed(range(len(futures))):
            if not futures[index].cancel():     # started: so are the calls before it (taken in order)
                break
            taken[index] = work(*calls[index])
        results = [taken[index] if index in taken else outcome(future) for index, future in enumerate(futures)]
    except BaseException:
        side.stop()
        raise
    side.close()
    return results, mine


def shared_map(work: Callable[..., Call], calls: Sequence[tuple]) -> list[Call]:
    """``share_calls`` with nothing else to do here: the calls' results in their order (one call is made here: a
    side process would only add its start)."""
    if len(calls) < 2:
        return [work(*call) for call in calls]
    return share_calls(work, calls, _nothing)[0]


def _nothing() -> None:
    return None

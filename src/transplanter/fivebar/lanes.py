"""Candidates refined in two fixed lanes: lane k takes candidates k, k + 2, k + 4, ... in order, each
lane on its own design solver, fresh when the lane starts (``DesignSolver`` carries the exchange
turns of one candidate to the next, which makes later candidates of a lane about three times
cheaper than its first). The return-stroke re-solves of the alternatives run in the same lanes
(``alternatives._other_strokes``), two at a time.

Lane 1 runs in a side process (``side_process``: forked, on Linux where this process may use a second
core) beside lane 0 in this one, on the solver this process built, copied unused at the fork. Elsewhere,
on one core, where the system refuses the process, or within ``lanes_here()`` (a study with a worker per
core, where the workers are the parallelism), lane 1 runs after lane 0 here, on ``new_solver()`` called
before lane 0 starts (in the package a twin of the unused solver that shares its built Functions:
``DesignSolver.twin``). Which lane refines which candidate from which solver state is the same either
way, so the outcome depends neither on the machine nor on timing. Processes, not threads: IPOPT's
iteration callback and the whole-turn checks between solves are Python, and two lanes in threads
contended for the interpreter lock (7 % gained, measured).
"""
from __future__ import annotations

import time
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, Future, wait

from transplanter.fivebar.design_solver import DesignSolver
from transplanter.side_process import in_this_process, outcome, start_side_process

LANES = 2
#: Within it, ``refine_in_lanes`` runs lane 1 after lane 0 in this process, never in a fork.
lanes_here = in_this_process

#: refine(solver, index) -> outcome: one candidate's refinement (its failures returned, not raised).
Refine = Callable[[DesignSolver, int], object]
#: finished(index, outcome, seconds): called in the caller's thread as each candidate is done.
Finished = Callable[[int, object, float], None]


def refine_in_lanes(count: int, refine: Refine, solver: DesignSolver, new_solver: Callable[[], DesignSolver],
                    finished: Finished) -> None:
    """Refine candidates 0 .. ``count`` - 1 in the lanes (module docstring): lane 0 on ``solver`` (left
    with lane 0's exchange turns), lane 1 on a fork of it or on ``new_solver()``, called before lane 0."""
    own, other = range(0, count, LANES), range(1, count, LANES)
    started = start_side_process(lambda index: _timed(refine, solver, index), [(index,) for index in other])
    # the fork happens at the first call, before lane 0 touches the solver
    side, futures = started if started is not None else (None, [])
    pending = dict(zip(futures, other, strict=False))
    second = new_solver() if side is None and other else None
    try:
        for index in own:
            finished(index, *_timed(refine, solver, index))
            _collect(pending, finished, timeout=0)
        while pending:
            _collect(pending, finished, timeout=None)
    except BaseException:       # an interrupt, or ``finished`` raising: lane 1 is stopped, not waited for
        if side is not None:
            side.stop()
        raise
    if side is not None:
        side.close()
    if second is not None:
        for index in other:
            finished(index, *_timed(refine, second, index))


def _timed(refine: Refine, solver: DesignSolver, index: int) -> tuple[object, float]:
    start = time.perf_counter()
    outcome = refine(solver, index)
    return outcome, time.perf_counter() - start


def _collect(pending: dict[Future, int], finished: Finished, timeout: float | None) -> None:
    """Report the forked lane's candidates that are done (waiting up to ``timeout`` s for one); an
    exception raised in the lane is raised here."""
    done, _ = wait(pending, timeout=timeout, return_when=FIRST_COMPLETED)
    for future in sorted(done, key=lambda future: pending[future]):
        finished(pending.pop(future), *outcome(future))

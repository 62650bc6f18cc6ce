"""Candidates refined in two fixed lanes: lane k takes candidates k, k + 2, k + 4, ... in order, each
lane on its own design solver, fresh when the lane starts (``DesignSolver`` carries the exchange
turns of one candidate to the next, which makes later candidates of a lane about three times
cheaper than its first).

On Linux lane 1 runs in a forked process beside lane 0 in this one, on the solver this process
built, copied unused at the fork. Elsewhere, where the system refuses the process, or within
``lanes_here()`` (a study with a worker per core, where the workers are the parallelism), lane 1 runs
after lane 0 here, on ``new_solver()`` called before lane 0 starts (in the package a twin of the
unused solver that shares its built Functions: ``DesignSolver.twin``). Which lane refines which
candidate from which solver state is the same either way, so the outcome depends neither on the
platform nor on timing. Processes, not threads: IPOPT's iteration callback and the whole-turn checks
between solves are Python, and two lanes in threads contended for the interpreter lock (7 % gained,
measured).
"""
from __future__ import annotations

import contextlib
import multiprocessing
import signal
import sys
import time
from collections.abc import Callable, Iterator
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from contextvars import ContextVar

from transplanter.fivebar.design_solver import DesignSolver

LANES = 2
#: Lane 1 in a forked process: on Linux only (macOS lists fork, but its system libraries are not
#: safe to use in a forked child).
FORKS = sys.platform.startswith("linux")
#: Whether lane 1 may fork here: ``lanes_here()`` turns it off for the calls within it (per thread).
_may_fork: ContextVar[bool] = ContextVar("may_fork", default=True)

#: refine(solver, index) -> outcome: one candidate's refinement (its failures returned, not raised).
Refine = Callable[[DesignSolver, int], object]
#: finished(index, outcome, seconds): called in the caller's thread as each candidate is done.
Finished = Callable[[int, object, float], None]

_forked: tuple[Refine, DesignSolver] | None = None      # lane 1's work, inherited by the forked process


@contextlib.contextmanager
def lanes_here() -> Iterator[None]:
    """Within it, ``refine_in_lanes`` runs lane 1 after lane 0 in this process, never in a fork."""
    token = _may_fork.set(False)
    try:
        yield
    finally:
        _may_fork.reset(token)


def refine_in_lanes(count: int, refine: Refine, solver: DesignSolver, new_solver: Callable[[], DesignSolver],
                    finished: Finished) -> None:
    """Refine candidates 0 .. ``count`` - 1 in the lanes (module docstring): lane 0 on ``solver`` (left
    with lane 0's exchange turns), lane 1 on a fork of it or on ``new_solver()``, called before lane 0."""
    global _forked
    own, other = range(0, count, LANES), range(1, count, LANES)
    _forked = (refine, solver)
    try:
        pool, pending = _fork_lane(other)
        second = new_solver() if pool is None and other else None
        try:
            for index in own:
                finished(index, *_timed(refine, solver, index))
                _collect(pending, finished, timeout=0)
            while pending:
                _collect(pending, finished, timeout=None)
        except BaseException:       # an interrupt, or ``finished`` raising: lane 1 is stopped, not waited for
            if pool is not None:
                _stop(pool)
            raise
        if pool is not None:
            pool.shutdown()
        if second is not None:
            for index in other:
                finished(index, *_timed(refine, second, index))
    finally:
        _forked = None


def _fork_lane(other: range) -> tuple[ProcessPoolExecutor | None, dict[Future, int]]:
    """A forked process refining the candidates ``other`` of lane 1, and their futures; (None, {}) where
    there is no lane 1, the platform does not fork, or the system refuses the process or its
    semaphores (a sandbox): lane 1 then runs here."""
    if not other or not FORKS or not _may_fork.get():
        return None, {}
    pool = None
    try:
        pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"), initializer=_lane_signals)
        # the fork happens at the first submit, before lane 0 touches the solver
        return pool, {pool.submit(_forked_lane, index): index for index in other}
    except OSError:
        if pool is not None:
            pool.shutdown(wait=False, cancel_futures=True)
        return None, {}


def _lane_signals() -> None:
    """In the forked lane: Ctrl-C (sent to the whole process group) is left to this process's parent, which
    stops the lane; the parent's SIGTERM ends it at once, as by default."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _stop(pool: ProcessPoolExecutor) -> None:
    """End the forked lane now: its queued candidates cancelled and its process terminated (a shutdown alone
    waits for the candidate it is on and the ones already handed to it)."""
    processes = list(getattr(pool, "_processes", {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        process.terminate()


def _forked_lane(index: int) -> tuple[object, float]:
    assert _forked is not None, "set by refine_in_lanes before the fork"
    refine, solver = _forked
    return _timed(refine, solver, index)


def _timed(refine: Refine, solver: DesignSolver, index: int) -> tuple[object, float]:
    start = time.perf_counter()
    outcome = refine(solver, index)
    return outcome, time.perf_counter() - start


def _collect(pending: dict[Future, int], finished: Finished, timeout: float | None) -> None:
    """Report the forked lane's candidates that are done (waiting up to ``timeout`` s for one); an
    exception raised in the lane is raised here."""
    done, _ = wait(pending, timeout=timeout, return_when=FIRST_COMPLETED)
    for future in sorted(done, key=lambda future: pending[future]):
        finished(pending.pop(future), *future.result())

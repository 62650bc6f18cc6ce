"""Work done in a forked process beside this one, where the machine gives this process a second core.

On Linux, where this process may run on more than one core (``os.sched_getaffinity``: ``taskset``, a
container's or a scheduler's CPU set), ``start_side_process(work, calls)`` forks one process that runs
``work(*call)`` for each call and hands back the results, the warnings it raised, its progress lines (shown
here as each call is collected) and its exceptions (raised here, as the same class with the same message).
Elsewhere, within ``in_this_process()`` (a study with a worker per core, where the workers are the
parallelism), or where the system refuses the process or its semaphores
(a sandbox), it gives None and the caller does the work here, in turn. The fork copies this process as it is,
so ``work`` may be a closure over objects that do not pickle (CasADi Functions); only calls and results cross.

``twinned(work)`` runs the same ``work`` here and in a side process at once, in step: each shares the work by
its ``Twin`` (which of the two it is) and swaps what it did for what the other did (``Twin.swap``); this
process's result is kept.

The forked process ignores Ctrl-C (sent to the whole process group): its parent stops it (``SideProcess.stop``)
and waits until it has ended, so nothing of it outlives the run or writes after the run has cleaned up.
"""
from __future__ import annotations

import contextlib
import multiprocessing
import os
import pickle
import signal
import sys
import warnings
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import BrokenExecutor, Future, ProcessPoolExecutor
from contextvars import ContextVar
from functools import partial
from multiprocessing.connection import Connection
from multiprocessing.reduction import ForkingPickler
from typing import Any, TypeVar

from transplanter import progress
from transplanter.errors import TransplanterError

#: A side process on Linux only (macOS lists fork, but its system libraries are not safe to use in a forked child).
FORKS = sys.platform.startswith("linux")
#: Whether a side process may be forked here: ``in_this_process()`` turns it off for the calls within it.
_may_fork: ContextVar[bool] = ContextVar("may_fork", default=True)

#: The signals that stop a run (Ctrl-C, and SIGTERM from a scheduler or ``SideProcess.stop``).
_STOPPING = {signal.SIGINT, signal.SIGTERM}

#: One warning raised in the side process: message, category, file name, line number.
Warned = tuple[Warning | str, type[Warning], str, int]

_work: Callable[..., Any] | None = None     # set in the side process only, by ``_install``

Here = TypeVar("Here")


@contextlib.contextmanager
def in_this_process() -> Iterator[None]:
    """Within it, ``start_side_process`` forks nothing: the callers do their side's work here, in turn."""
    token = _may_fork.set(False)
    try:
        yield
    finally:
        _may_fork.reset(token)


def usable_cores() -> int:
    """The cores this process may run on (its CPU affinity where the system has one, else the machine's)."""
    if hasattr(os, "sched_getaffinity"):
        return len(os.sched_getaffinity(0))
    return os.cpu_count() or 1


def may_fork() -> bool:
    """Whether a side process would run beside this one: Linux, outside ``in_this_process()``, two cores or more."""
    return FORKS and _may_fork.get() and usable_cores() > 1


class SideProcess:
    """A forked process running one ``work``; its results come back through ``Future``s."""

    def __init__(self, work: Callable[..., Any]):
        self._pool = ProcessPoolExecutor(1, mp_context=multiprocessing.get_context("fork"), initializer=_install,
                                         initargs=(work,))     # a forked child inherits initargs, nothing pickled

    def submit(self, *call: Any) -> Future:
        """``work(*call)`` in the side process: the Future to pass to ``outcome``. The first forks the process, with
        Ctrl-C and SIGTERM held until ``_install`` has set its own handling of them: a signal that came before (a
        ``stop`` right after the start) ran this process's handler there, which printed its traceback or, raised
        just after the fork, took the copy back into this process's code (a test run waited for ever on it)."""
        held = signal.pthread_sigmask(signal.SIG_BLOCK, _STOPPING)
        try:
            return self._pool.submit(_run_work, *call)
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)

    def close(self) -> None:
        """Wait for the submitted calls, then end the process."""
        self._pool.shutdown()

    def stop(self) -> None:
        """End the process now (its queued calls cancelled, the one it is on cut short) and wait until it has."""
        processes = list(getattr(self._pool, "_processes", {}).values())
        manager = getattr(self._pool, "_executor_manager_thread", None)
        self._pool.shutdown(wait=False, cancel_futures=True)
        for process in processes:
            process.terminate()
        for process in processes:
            process.join()
        if manager is not None:     # its threads ended too: a thread still holding a lock at the next fork would
            manager.join()          # leave that lock held in the forked child, which then waits for ever


def start_side_process(work: Callable[..., Any], calls: Sequence[tuple]) -> tuple[SideProcess, list[Future]] | None:
    """A side process running ``work(*call)`` for each of ``calls`` (forked at the first) and their Futures, in
    order; None where no side process may run (``may_fork``) or the system refuses one."""
    if not calls or not may_fork():
        return None
    side = None
    try:
        side = SideProcess(work)
        return side, [side.submit(*call) for call in calls]
    except OSError:
        if side is not None:
            side.stop()
        return None


def outcome(future: Future) -> Any:
    """The result of a call in the side process, its warnings raised here as they were (the run prints or records
    them) and its progress lines shown here; its exception raised here."""
    try:
        result, warned, said = future.result()
    except BrokenExecutor:
        raise TransplanterError("a side process of this run ended before it gave its result (killed from outside, "
                                "or the system ran out of memory); expected it to finish: run again") from None
    for message, category, filename, lineno in warned:
        warnings.warn_explicit(message, category, filename, lineno)
    progress.show(said)
    return result


class Twin:
    """One of the two processes running the same work in step (``twinned``): its ``index`` (0 here, 1 in the side
    process) and the connection to the other."""

    def __init__(self, index: int, connection: Connection, side: Future | None = None):
        self.index = index
        self._connection = connection
        self._side = side           # here: the side process's call, whose error a broken swap raises

    def swap(self, value: Any) -> Any:
        """The other process's ``value`` for this one's, both at the same step of their work. This process sends
        first and the side process receives first, so neither waits to send while the other does. Here, where the
        side process ended before it swapped, its error is raised."""
        try:
            if self.index == 0:
                self._connection.send(value)
                return self._connection.recv()
            theirs = self._connection.recv()
            self._connection.send(value)
            return theirs
        except (EOFError, OSError):
            if self._side is None:
                raise
            outcome(self._side)
            raise TransplanterError("a side process ended its work without swapping what it did; expected both "
                                    "processes to run the same steps") from None


def twinned(work: Callable[[Twin | None], Here]) -> Here:
    """``work(twin)`` here and in a side process at once (``twin.index`` 0 and 1), in step; this process's result.
    The side process's result, warnings and progress lines are dropped (this process gives its own); its error,
    where it ends before a swap, is raised here. Where no side process may run, ``work(None)`` here."""
    if not may_fork():
        return work(None)
    here, there = multiprocessing.Pipe()
    started = start_side_process(partial(_twin_there, work, there, here), [()])
    there.close()                   # the side process holds its own end: its ending closes the pipe
    if started is None:
        here.close()
        return work(None)
    side, (future,) = started
    try:
        return work(Twin(0, here, future))
    finally:
        side.stop()                 # what is left of its work repeats this process's
        here.close()


def _twin_there(work: Callable[[Twin], Any], there: Connection, here: Connection) -> None:
    """In the side process: ``work`` as twin 1, its end of the pipe closed when it returns or raises."""
    here.close()
    try:
        work(Twin(1, there))
    finally:
        there.close()


def _install(work: Callable[..., Any]) -> None:
    """In the side process: its work, and its signals (Ctrl-C left to the parent, SIGTERM ending it at once), then
    let through (held since the fork: ``SideProcess.submit``)."""
    global _work
    _work = work
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, _STOPPING)


def _run_work(*call: Any) -> tuple[Any, list[Warned], str]:
    """In the side process: one call of the work, with the warnings it raised and the progress lines it would have
    shown; an exception made to cross."""
    assert _work is not None, "installed when the process starts"
    try:
        with warnings.catch_warnings(record=True) as log, progress.held() as said:
            result = _work(*call)
    except Exception as error:
        _let_cross(error)
        raise
    return result, [(w.message, w.category, w.filename, w.lineno) for w in log], said.getvalue()


def _let_cross(error: BaseException) -> None:
    """Make ``error`` pickle to its own class with its message, even where its ``__init__`` takes other arguments
    than its ``args`` (``SolverError``): rebuilt from its state instead (in the side process only)."""
    with contextlib.suppress(Exception):
        pickle.loads(pickle.dumps(error))
        return
    ForkingPickler.register(type(error), _by_state)


def _by_state(error: BaseException):
    return _rebuilt, (type(error), error.args, vars(error))


def _rebuilt(kind: type[BaseException], args: tuple, state: dict) -> BaseException:
    error = kind.__new__(kind, *args)
    error.args = args
    vars(error).update(state)
    return error

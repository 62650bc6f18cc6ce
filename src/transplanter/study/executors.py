"""Where the cases run: local worker processes (made and owned by the study), an Executor the caller gives,
or a Dask cluster (``distributed.Client``, used through its ``concurrent.futures`` face)."""
from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
from concurrent.futures import Executor, ProcessPoolExecutor
from pathlib import Path
from typing import Any

from transplanter.cores import usable_cores
from transplanter.errors import ProblemError

#: Seconds to wait for a Dask scheduler before calling it unreachable.
CONNECT_TIMEOUT_S = 5.0


def _ignore_interrupt():
    """Workers leave Ctrl-C to the study, which stops them (a worker's KeyboardInterrupt would be a case's)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _descendants(pid: int | None) -> list[int]:
    """The processes ``pid`` started, and theirs (Linux: /proc; none elsewhere)."""
    children = []
    for task in Path(f"/proc/{pid}/task").glob("*/children"):
        with contextlib.suppress(OSError):
            children += [int(child) for child in task.read_text().split()]
    return [pid for child in children for pid in (*_descendants(child), child)]


class LocalWorkers:
    """A pool of worker processes the study owns: it can kill them (a case past its timeout, Ctrl-C) and start
    new ones (after a worker died, the pool is broken). Spawned, not forked: a fork copies the solver threads'
    state of the parent."""

    def __init__(self, workers: int | None = None):
        self.workers = workers or usable_cores()
        self.executor = self._start()

    def _start(self) -> ProcessPoolExecutor:
        return ProcessPoolExecutor(self.workers, mp_context=multiprocessing.get_context("spawn"),
                                   initializer=_ignore_interrupt)

    def stop(self):
        """Kill the workers and the processes they started (the five-bar's second lane is a fork of its
        worker) at once, their cases lost, and free the pool."""
        # the pool has no public way to end a running call: its processes are killed one by one
        workers = list((getattr(self.executor, "_processes", None) or {}).values())
        for pid in [pid for worker in workers for pid in (*_descendants(worker.pid), worker.pid)]:
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
        self.executor.shutdown(wait=False, cancel_futures=True)
        for worker in workers:
            worker.join(timeout=5)

    def restart(self):
        """New workers in place of killed or dead ones."""
        self.stop()
        self.executor = self._start()


def dask_client(scheduler: str) -> Any:
    """A ``distributed.Client`` of the cluster at ``scheduler``; ProblemError when distributed is not installed or
    the scheduler does not answer within ``CONNECT_TIMEOUT_S``."""
    try:
        from distributed import Client
    except ImportError:
        raise ProblemError(f"scheduler = {scheduler}: a Dask cluster needs the distributed package; expected it "
                           "installed (pip install 'transplanter[cluster]')") from None
    try:
        return Client(scheduler, timeout=f"{CONNECT_TIMEOUT_S}s")
    except (OSError, TimeoutError, ValueError) as error:
        raise ProblemError(f"scheduler = {scheduler}: unreachable ({' '.join(str(error).split())[:200]}); expected "
                           "the address of a running Dask scheduler such as tcp://HOST:8786") from None


def as_executor(executor: Any) -> tuple[Executor, int]:
    """``executor`` as a ``concurrent.futures.Executor`` (a ``distributed.Client`` gives its own) and how many
    cases it runs at once (the cluster's threads, the pool's workers, or one per core)."""
    if isinstance(executor, Executor):
        return executor, getattr(executor, "_max_workers", None) or usable_cores()
    if hasattr(executor, "get_executor") and hasattr(executor, "nthreads"):
        return executor.get_executor(pure=False), max(1, sum(executor.nthreads().values()))
    raise ProblemError(f"executor = {type(executor).__name__}: expected a concurrent.futures.Executor or a "
                       "distributed.Client")

"""A worker's memory over one case: its peak while the case ran and what it holds after, with the heap the case
freed given back to the system.

A five-bar case frees 80-180 MB when it ends (its NLPs, solvers and arrays), which glibc's allocator keeps for later
allocations: ten cases of the bundled five-bar study in a row in one process left 382-447 MB resident after each,
and 214-247 MB with ``malloc_trim`` after each (which returns the free pages), with as many CasADi Functions held by
Python objects after every case. The peak is Linux's VmHWM, reset at the case's start (``/proc/self/clear_refs``), so it
is the case's own, not the largest of the worker's cases so far (where one process runs several cases at once, a
Dask worker's threads, it is the process's since the latest of them began). Elsewhere (no /proc, no glibc) the
numbers are None and nothing is trimmed.

A worker's allocator keeps at most ``ARENAS`` heaps (glibc's ``M_ARENA_MAX``; by default a new thread gets a heap
of its own, up to eight per core, and a five-bar case cuts its gear stages on two threads): each heap keeps its own
freed pages in part, out of the trim's reach. Two workers side by side, each running 64 cases of the bundled
five-bar study in turn: with three heaps resident after each case 217-315 MB, rising (313-315 MB after the last
ten); with two 217-227 MB (217-219 after the last forty).
"""
from __future__ import annotations

import contextlib
import ctypes
import gc
import os
import platform
from collections.abc import Iterator
from pathlib import Path

_STATUS, _CLEAR_REFS = Path("/proc/self/status"), Path("/proc/self/clear_refs")
#: The most heaps a worker's allocator keeps (module docstring), and glibc's ``mallopt`` parameter that sets it.
ARENAS, _M_ARENA_MAX = 2, -8
_GLIBC = platform.libc_ver()[0] == "glibc"
#: What ``/proc/self/clear_refs`` takes to set the peak resident memory to the present one.
_RESET_PEAK = "5"


def _status_mb() -> tuple[float | None, float | None]:
    """(resident, peak resident) memory of this process in MB, None where /proc does not give them."""
    try:
        lines = _STATUS.read_text().splitlines()
    except OSError:
        return None, None
    fields = dict(line.split(":", 1) for line in lines if ":" in line)

    def megabytes(name: str) -> float | None:
        return int(fields[name].split()[0]) / 1024 if name in fields else None

    return megabytes("VmRSS"), megabytes("VmHWM")


def _glibc_function(name: str):
    """glibc's function ``name`` in this process, None where the C library is another (Windows loads none by
    ``CDLL(None)``; macOS's and musl's take other ``mallopt`` parameters)."""
    return getattr(ctypes.CDLL(None), name, None) if _GLIBC else None


def _limit_heaps():
    """At most ``ARENAS`` allocator heaps from now on (module docstring), where glibc lets it be set."""
    mallopt = _glibc_function("mallopt")
    if mallopt is not None:
        mallopt(_M_ARENA_MAX, ARENAS)


def _return_free_heap():
    """Collect garbage, then give the allocator's free pages back to the system (glibc's ``malloc_trim``)."""
    gc.collect()
    trim = _glibc_function("malloc_trim")
    if trim is not None:
        trim(0)


@contextlib.contextmanager
def case_memory() -> Iterator[dict[str, float | int | None]]:
    """Around one case: yields a dict that holds, once the block ends, the worker's ``pid``, its ``peak_mb`` while
    the block ran and its ``resident_mb`` after it (the freed heap returned first). From the first block on, the
    process's allocator keeps at most ``ARENAS`` heaps."""
    _limit_heaps()
    with contextlib.suppress(OSError):      # a kernel that refuses: the peak is then the worker's since it started
        _CLEAR_REFS.write_text(_RESET_PEAK)
    memory: dict[str, float | int | None] = {"pid": os.getpid()}
    try:
        yield memory
    finally:
        memory["peak_mb"] = _status_mb()[1]
        _return_free_heap()
        memory["resident_mb"] = _status_mb()[0]

"""A worker's memory over one case: its peak while the case ran and what it holds after, with the heap the case
freed given back to the system.

A five-bar case frees 80-180 MB when it ends (its NLPs, solvers and arrays), which glibc's allocator keeps for later
allocations: ten cases of the bundled five-bar study in a row in one process left 382-447 MB resident after each,
and 214-247 MB with ``malloc_trim`` after each (which returns the free pages), with as many CasADi Functions held by
Python objects after every case. The peak is Linux's VmHWM, reset at the case's start (``/proc/self/clear_refs``), so it
is the case's own, not the largest of the worker's cases so far (where one process runs several cases at once, a
Dask worker's threads, it is the process's since the latest of them began). Elsewhere (no /proc, no glibc) the
numbers are None and nothing is trimmed.
"""
from __future__ import annotations

import contextlib
import ctypes
import gc
import os
from collections.abc import Iterator
from pathlib import Path

_STATUS, _CLEAR_REFS = Path("/proc/self/status"), Path("/proc/self/clear_refs")
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


def _return_free_heap():
    """Collect garbage, then give the allocator's free pages back to the system (glibc's ``malloc_trim``)."""
    gc.collect()
    trim = getattr(ctypes.CDLL(None), "malloc_trim", None)
    if trim is not None:
        trim(0)


@contextlib.contextmanager
def case_memory() -> Iterator[dict[str, float | int | None]]:
    """Around one case: yields a dict that holds, once the block ends, the worker's ``pid``, its ``peak_mb`` while
    the block ran and its ``resident_mb`` after it (the freed heap returned first)."""
    with contextlib.suppress(OSError):      # a kernel that refuses: the peak is then the worker's since it started
        _CLEAR_REFS.write_text(_RESET_PEAK)
    memory: dict[str, float | int | None] = {"pid": os.getpid()}
    try:
        yield memory
    finally:
        memory["peak_mb"] = _status_mb()[1]
        _return_free_heap()
        memory["resident_mb"] = _status_mb()[0]

"""How many cores this process may use: the ones its CPU affinity allows (``taskset``, a container's cpuset),
where the system keeps one, else all the machine's."""
from __future__ import annotations

import os


def usable_cores() -> int:
    """The cores this process may run on (at least one)."""
    if hasattr(os, "sched_getaffinity"):
        return max(1, len(os.sched_getaffinity(0)))
    return os.cpu_count() or 1

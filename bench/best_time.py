"""The best of several in-process runs of a function (the benches' timer)."""
from __future__ import annotations

import time


def best_time(function, repeat: int):
    """Smallest wall time (s) of ``repeat`` calls of ``function()``, and the last call's value."""
    best, value = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        value = function()
        best = min(best, time.perf_counter() - start)
    return best, value

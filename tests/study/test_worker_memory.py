"""A worker's memory over a case: the case's own peak, and the heap the case freed given back."""
from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from transplanter.study.worker_memory import case_memory

pytestmark = pytest.mark.skipif(not Path("/proc/self/clear_refs").exists(), reason="Linux's /proc gives the numbers")

#: Memory a test allocates (MB), well above what the rest of a test process moves meanwhile.
MB = 200


def _resident_mb() -> float:
    return next(int(line.split()[1]) / 1024 for line in Path("/proc/self/status").read_text().splitlines()
                if line.startswith("VmRSS:"))


def test_the_peak_is_the_cases_own_not_the_workers_since_it_started():
    block = np.ones(MB * 2**20 // 8)        # one mapping, given back when freed: it raises only the peak
    del block
    start = _resident_mb()
    with case_memory() as memory:
        pass
    assert memory["pid"] == os.getpid()
    assert memory["peak_mb"] < start + MB / 4


def test_freed_heap_that_a_live_block_pins_is_given_back_after_the_case():
    with case_memory() as memory:
        pieces = [np.ones(1250) for _ in range(MB * 100)]   # 10 KB each: from the heap, not mappings of their own
        pin = np.ones(1250)                                 # allocated above them and kept: the heap cannot shrink
        before = _resident_mb()
        del pieces
    assert before - memory["resident_mb"] > MB / 2
    assert memory["peak_mb"] >= before - 1
    assert pin.sum() == 1250

"""A worker's memory over a case: the case's own peak, and the heap the case freed given back."""
from __future__ import annotations

import os
import platform
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from transplanter.study.worker_memory import ARENAS, case_memory

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


#: In a fresh Python: eight threads allocate at once inside a case, then the allocator's heaps are counted (glibc's
#: malloc_info lists each heap as ``<heap nr=``); by default each thread would get a heap of its own.
HEAPS_OF_EIGHT_THREADS = textwrap.dedent("""
    import ctypes, threading
    import numpy as np
    from transplanter.study.worker_memory import case_memory

    libc = ctypes.CDLL(None)
    libc.open_memstream.restype = ctypes.c_void_p
    start = threading.Barrier(8)

    def allocate():
        start.wait()
        for _ in range(200):
            pieces = [np.ones(100) for _ in range(50)]
            del pieces

    with case_memory():
        threads = [threading.Thread(target=allocate) for _ in range(8)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
    text, size = ctypes.c_char_p(), ctypes.c_size_t()
    stream = ctypes.c_void_p(libc.open_memstream(ctypes.byref(text), ctypes.byref(size)))
    libc.malloc_info(0, stream)
    libc.fclose(stream)
    print(ctypes.string_at(text, size.value).decode().count("<heap nr="))
""")


@pytest.mark.skipif(platform.libc_ver()[0] != "glibc", reason="glibc's allocator")
def test_a_worker_keeps_at_most_its_heaps_however_many_threads_allocate():
    child = subprocess.run([sys.executable, "-c", HEAPS_OF_EIGHT_THREADS], capture_output=True, text=True,
                           timeout=120, check=True)
    assert int(child.stdout) <= ARENAS

"""A study worker's memory over many cases: the package's worker against one whose allocator keeps a heap per
thread (glibc's default), side by side.

    python bench/bench_worker_memory.py [--cases 64]

Two spawned processes run at the same time, each ``--cases`` cases of
examples/vegetable_planting_variants_study.toml in turn (a Latin hypercube of twice that many samples, dealt
alternately), each case as a study's worker runs it (``study.case_run.run_case``, both lanes in the worker). The
baseline worker is the package's but for the limit on its allocator's heaps (``study.worker_memory``'s
``_limit_heaps`` left out). Printed for each: its peak while each case ran and its resident memory after it (the
case's ``worker_memory`` record) with their trends (MB per case, least squares; target: flat), and the allocator's
heaps and the bytes it holds in use after the last case (glibc's ``mallinfo2``: what a leak would raise, where
the resident memory also counts freed pages the trim could not return). Linux with glibc only.
"""
from __future__ import annotations

import argparse
import ctypes
import json
import multiprocessing
import tempfile
import time
from dataclasses import replace
from pathlib import Path

from bench_study import print_memory

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples/vegetable_planting_variants_study.toml"


class _AllocatorInfo(ctypes.Structure):
    """glibc's ``struct mallinfo2``."""
    _fields_ = [(name, ctypes.c_size_t) for name in ("arena", "ordblks", "smblks", "hblks", "hblkhd", "usmblks",
                                                     "fsmblks", "uordblks", "fordblks", "keepcost")]


def _allocator() -> dict[str, float]:
    """The allocator's heaps (counted in ``malloc_info``'s listing) and the MB it holds in use."""
    libc = ctypes.CDLL(None)
    libc.mallinfo2.restype = _AllocatorInfo
    libc.open_memstream.restype = ctypes.c_void_p
    text, size = ctypes.c_char_p(), ctypes.c_size_t()
    stream = ctypes.c_void_p(libc.open_memstream(ctypes.byref(text), ctypes.byref(size)))
    libc.malloc_info(0, stream)
    libc.fclose(stream)
    heaps = ctypes.string_at(text, size.value).decode().count("<heap nr=")
    libc.free(text)
    return {"heaps": heaps, "in_use_mb": libc.mallinfo2().uordblks / 2**20}


def _study_cases(samples: int):
    from transplanter.study import load_study
    from transplanter.study.cases import study_cases

    spec = replace(load_study(EXAMPLE), samples=samples)
    return spec, study_cases(spec)


def _worker(limited: bool, samples: int, first: int, record: Path):
    """Run every second case from ``first``, appending each case's memory record to ``record``."""
    from transplanter.study import worker_memory
    from transplanter.study.case_run import run_case
    from transplanter.study.runner import _case_source

    if not limited:
        worker_memory._limit_heaps = lambda: None
    spec, cases = _study_cases(samples)
    with record.open("a") as lines:
        for case in cases[first::2]:
            memory = run_case(spec.command, case.problem, _case_source(spec, case), False)["memory"]
            lines.write(json.dumps({**memory, **_allocator()}) + "\n")
            lines.flush()


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=64, help="cases per worker")
    cases = parser.parse_args().cases
    spawn = multiprocessing.get_context("spawn")
    with tempfile.TemporaryDirectory() as folder:
        records = {name: Path(folder) / f"{name}.jsonl" for name in ("package", "baseline")}
        start = time.perf_counter()
        workers = [spawn.Process(target=_worker, args=(name == "package", 2 * cases, first, records[name]))
                   for first, name in enumerate(records)]
        for worker in workers:
            worker.start()
        for worker in workers:
            worker.join()
        print(f"{cases} cases per worker, two workers side by side: {time.perf_counter() - start:.0f} s")
        for name, path in records.items():
            rows = [json.loads(line) for line in path.read_text().splitlines()]
            print_memory(f"{name} ({'at most two heaps' if name == 'package' else 'a heap per thread'})",
                         {rows[0]["pid"]: [(row["peak_mb"], row["resident_mb"]) for row in rows]})
            print(f"  after the last case: {rows[-1]['heaps']} heaps, {rows[-1]['in_use_mb']:.1f} MB in use "
                  f"(after the first: {rows[0]['in_use_mb']:.1f} MB)")


if __name__ == "__main__":
    main()

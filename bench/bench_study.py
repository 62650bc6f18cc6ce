"""Time a study of the five-bar example with its key poses shifted a little: two workers against one, the
scheduling overhead, each worker's memory over the cases, and a resume after a kill.

    python bench/bench_study.py [--cases 64] [--resume-cases 8] [--one-core-only] [--keep DIR]

- The cases: examples/vegetable_planting_variants_study.toml (most of its cases give a design) with ``--cases``
  Latin hypercube samples, run on one local worker pinned to one core, on one worker with every core, and on
  two workers, in this process (the same cases, the same table: checked). A five-bar case refines its
  candidates in two lanes: where the study runs fewer cases at once than the process has cores, the second
  lane is a forked process; otherwise both lanes run in the worker, the workers being the parallelism. So
  one worker on a 2-core machine already uses both cores for part of each case, and two workers gain only the
  rest: the target (two workers at most 0.6 of one) is measured against one worker on one core, where a
  worker is a core's worth of work; the ratio against one worker with both cores is printed beside it
  (``--one-core-only`` skips that run). Printed: the wall times to the last case recorded and the ratios;
  the scheduling overhead of the pinned one-worker run, its wall time beyond the cases' own seconds, against
  those seconds (target: under 5 %), split into the checks of every case before any runs, the worker's
  start-up (its imports) and the time between cases; and the share of the cases' own seconds that builds
  the design NLP (a build per case: the NLP is the problem's). The load average is printed before and after:
  the ratios mean little on a machine others load.
- Memory: each worker's peak memory while each of its cases ran and its resident memory after it (the
  cases' report.json, ``worker_memory``), in the order it ran them, with the trend of each series (MB per case,
  least squares) (target: flat, no leak from the solver caches).
- Resume: ``transplanter study`` on ``--resume-cases`` cases, killed (SIGKILL, the whole process group) after
  a few cases, then ``--resume``: the cases lost and the cases run twice (target: 0 and 0).
"""
from __future__ import annotations

import argparse
import contextlib
import csv
import json
import os
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

import numpy as np

from transplanter.study import load_study, run
from transplanter.study.spec import StudySpec

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples/vegetable_planting_variants_study.toml"


def _spec(cases: int, workers: int) -> StudySpec:
    from dataclasses import replace

    spec = load_study(EXAMPLE)
    return replace(spec, samples=cases, executor=replace(spec.executor, workers=workers))


def checks_seconds(spec: StudySpec) -> float:
    """The time the study takes to draw its cases and check each one's problem before any runs."""
    from transplanter.study.cases import study_cases
    from transplanter.study.runner import _check_cases

    start = time.perf_counter()
    _check_cases(spec, study_cases(spec))
    return time.perf_counter() - start


def build_seconds(folder: Path) -> float:
    """The seconds the cases of the study in ``folder`` spent building their design NLPs (their reports'
    timings)."""
    reports = (json.loads(path.read_text())["report"] for path in folder.glob("cases/*/report.json"))
    return sum(report.get("timings_s", {}).get("nlp_build", 0.0) for report in reports)


@contextlib.contextmanager
def one_core():
    """Within it this process and the workers it starts may run on its first allowed core only."""
    allowed = os.sched_getaffinity(0)
    os.sched_setaffinity(0, {min(allowed)})
    try:
        yield
    finally:
        os.sched_setaffinity(0, allowed)


def timed_study(cases: int, workers: int, folder: Path):
    """Run the study; its wall time to the last case recorded (the report and figures after it are not
    scheduling), the time until its first case started (checks, the workers' start-up), its rows and each
    worker's (peak while the case ran, resident after it) over its cases, in the order they were recorded."""
    memory: dict[int, list[tuple[float, float]]] = {}
    recorded = []

    def sample(row):
        recorded.append((time.perf_counter(), float(row["seconds"])))
        case = json.loads((folder / "cases" / row["case_id"] / "report.json").read_text())["worker_memory"]
        memory.setdefault(case["pid"], []).append((case["peak_mb"], case["resident_mb"]))

    start = time.perf_counter()
    outcome = run(_spec(cases, workers), folder, on_case=sample)
    first_started = recorded[0][0] - recorded[0][1] - start
    return recorded[-1][0] - start, first_started, outcome.rows, memory


def trend(series: list[float]) -> float:
    """The least-squares slope of ``series`` against its index (per case)."""
    return float(np.polyfit(np.arange(len(series)), series, 1)[0]) if len(series) > 1 else 0.0


def _ids(path: Path) -> list[str]:
    with path.open() as stream:
        return [row["case_id"] for row in csv.DictReader(stream)]


def killed_and_resumed(cases: int, folder: Path) -> tuple[int, int, int]:
    """Cases kept at the kill, lost, and run twice after ``--resume``."""
    folder.mkdir()
    study = folder / "study.toml"
    study.write_text(EXAMPLE.read_text().replace("samples = 8", f"samples = {cases}")
                     .replace('problem = "vegetable_planting.toml"',
                              f'problem = "{ROOT / "examples/vegetable_planting.toml"}"'))
    out = folder / "out"
    command = [sys.executable, "-m", "transplanter", "study", str(study), "--out", str(out), "--quiet"]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    while process.poll() is None and not ((out / "cases.csv").exists() and len(_ids(out / "cases.csv")) >= 2):
        time.sleep(0.1)
    os.killpg(process.pid, signal.SIGKILL)
    process.wait()
    kept = _ids(out / "cases.csv")
    subprocess.run([*command, "--resume"], check=True, stdout=subprocess.DEVNULL)
    ids = _ids(out / "cases.csv")
    twice = sum(count - 1 for count in Counter(ids).values())
    return len(kept), cases - len(set(ids)), twice


def print_memory(run_name: str, memory: dict[int, list[tuple[float, float]]]):
    """Each worker's peaks and resident memory over its cases, with their trends."""
    for pid, samples in memory.items():
        peaks, residents = ([sample[k] for sample in samples] for k in (0, 1))
        print(f"{run_name}, worker {pid}, its {len(samples)} cases: peak while each ran {min(peaks):.0f}-"
              f"{max(peaks):.0f} MB (trend {trend(peaks):+.2f} MB per case), resident after each "
              f"{min(residents):.0f}-{max(residents):.0f} MB (trend {trend(residents):+.2f} MB per case)\n"
              "  peaks (MB): " + " ".join(f"{peak:.0f}" for peak in peaks) + "\n  resident after (MB): "
              + " ".join(f"{resident:.0f}" for resident in residents))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--cases", type=int, default=64)
    parser.add_argument("--resume-cases", type=int, default=8)
    parser.add_argument("--one-core-only", action="store_true", help="skip the run of one worker with every core")
    parser.add_argument("--keep", type=Path, help="write the two-worker study (its report and figures) into this "
                        "new folder instead of a temporary one")
    args = parser.parse_args()
    print("load average (1, 5, 15 min) before: " + ", ".join(f"{load:.1f}" for load in os.getloadavg()))
    with tempfile.TemporaryDirectory() as temporary:
        folder = Path(temporary)
        checks = checks_seconds(_spec(args.cases, 1))
        with one_core():
            one, start_up, rows_one, memory_one = timed_study(args.cases, 1, folder / "one")
        every = None if args.one_core_only else timed_study(args.cases, 1, folder / "every")
        two, _, rows_two, memory = timed_study(args.cases, 2, args.keep or folder / "two")
        tables = [rows_one, rows_two] + ([] if every is None else [every[2]])
        same = len({tuple(sorted((r["case_id"], r["status"], r["transmission_angle_min_deg"]) for r in rows))
                    for rows in tables}) == 1
        case_seconds = sum(float(r["seconds"]) for r in rows_one)
        print(f"{args.cases} cases of the five-bar example, key poses moved a little "
              f"({Counter(r['status'] for r in rows_one)}); same table on every run: {same}")
        print(f"wall time: one worker on one core {one:.1f} s, two workers {two:.1f} s: ratio {two / one:.2f} "
              f"(target at most 0.6)")
        if every is not None:
            print(f"one worker with all {len(os.sched_getaffinity(0))} cores (its cases' second lanes forked) "
                  f"{every[0]:.1f} s: two workers take {two / every[0]:.2f} of it")
        between = one - start_up - case_seconds
        print(f"scheduling overhead (one worker, one core): {start_up:.1f} s to start the first case ({checks:.1f} s "
              f"checking the cases, {start_up - checks:.1f} s the worker's start-up), then {between:.1f} s between "
              f"cases beyond their own {case_seconds:.1f} s = {between / case_seconds:.1%}; with the start-up "
              f"{(one - case_seconds) / case_seconds:.1%} (target under 5 %)")
        built = build_seconds(folder / "one")
        print(f"inside the cases: {built:.1f} s building design NLPs = {built / case_seconds:.1%} of their seconds")
        print_memory("one worker on one core", memory_one)
        print_memory("two workers", memory)
        kept, lost, twice = killed_and_resumed(args.resume_cases, folder / "killed")
        print(f"killed after {kept} of {args.resume_cases} cases, resumed: {lost} cases lost, {twice} run twice "
              "(target 0 and 0)")
    print("load average (1, 5, 15 min) after: " + ", ".join(f"{load:.1f}" for load in os.getloadavg()))


if __name__ == "__main__":
    main()

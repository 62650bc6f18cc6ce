"""``run``: every case of a study on an executor, each result on disk as it finishes.

Nothing finished is lost: a case's report.json and its row of cases.csv are written when it finishes, so a
study stopped in any way (Ctrl-C, a kill, a crash) keeps them, and ``resume`` runs only the cases the table
lacks. A worker that dies takes the cases it was running with it: they are run again, alone (so a second
death is theirs), and recorded as crashed after ``attempts`` deaths. A case past ``case_timeout_s`` is
recorded as a timeout (local workers are killed and restarted; another executor's call is cancelled). Where
the executor runs as many cases at once as this machine has cores, a five-bar case runs both its refinement
lanes in its worker instead of forking the second (``case_run``): the workers are the parallelism.
"""
from __future__ import annotations

import time
from collections import deque
from collections.abc import Callable
from concurrent.futures import FIRST_COMPLETED, BrokenExecutor, Future, wait
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from transplanter.errors import TransplanterError
from transplanter.output_folder import report_json, staged_file
from transplanter.side_process import usable_cores
from transplanter.study.case_run import CRASHED, ERROR, TIMEOUT, run_case
from transplanter.study.cases import Case, study_cases
from transplanter.study.executors import LocalWorkers, as_executor, dask_client
from transplanter.study.folder import prepare_folder
from transplanter.study.progress_bar import ProgressBar
from transplanter.study.spec import StudySpec
from transplanter.study.summary import write_summary
from transplanter.study.table import append_row, columns, read_rows, row_of

#: Seconds between looks at the running cases (for timeouts) while none finishes.
TICK_S = 0.2
#: The statuses that say a case did not run to the command's own verdict.
UNFINISHED = (ERROR, TIMEOUT, CRASHED)


@dataclass(frozen=True)
class StudyOutcome:
    """What a study left in its folder: the table's rows (one per case) and how many cases ran now."""

    folder: Path
    rows: list[dict[str, str]]
    ran: int

    @property
    def unfinished(self) -> list[dict[str, str]]:
        """Rows of cases that timed out, crashed, or hit an error the command does not expect."""
        return [row for row in self.rows if row["status"] in UNFINISHED]


@dataclass
class _Running:
    case: Case
    attempts: int
    submitted: float


def _check_cases(spec: StudySpec, cases: list[Case]):
    """Refuse (ProblemError, naming the case and the field) a case whose problem the command would refuse."""
    from transplanter.cli import COMMANDS

    command = next(c for c in COMMANDS if c.name == spec.command)
    for case in cases:
        command.package.parse_problem(case.problem, _case_source(spec, case))


def _case_source(spec: StudySpec, case: Case) -> str:
    return f"{spec.problem_file} (case {case.case_id}: " + ", ".join(f"{k} = {v!r}" for k, v in case.values.items()) \
        + ")"


class _Study:
    """The bookkeeping of one run: the table, the reports, the progress bar, the callback."""

    def __init__(self, spec: StudySpec, folder: Path, bar: ProgressBar, on_case: Callable[[dict], None] | None):
        self.spec, self.folder, self.bar, self.on_case = spec, folder, bar, on_case
        self.header = columns(spec.fields, spec.collect)
        self.ran = 0

    def record(self, case: Case, outcome: dict[str, Any], attempts: int):
        report = outcome.get("report", {})
        case_folder = self.folder / "cases" / case.case_id
        case_folder.mkdir(exist_ok=True)
        with staged_file(case_folder / "report.json") as partial:
            partial.write_text(report_json({"case_id": case.case_id, "command": self.spec.command,
                                            "values": case.values, "status": outcome["status"],
                                            "exit_class": outcome.get("exit_class"), "error": outcome.get("error", ""),
                                            "warnings": outcome.get("warnings", []),
                                            "worker_memory": outcome.get("memory", {}), "report": report,
                                            "files": {"report": ["report.json"]}}) + "\n")
        row = row_of(case.case_id, case.values, outcome, attempts, self.spec.collect)
        append_row(self.folder / "cases.csv", self.header, row)
        self.ran += 1
        self.bar.advance(row["status"])
        if self.on_case:
            self.on_case(row)


def _loop(study: _Study, todo: deque[Case], executor, window: int, local: LocalWorkers | None):
    """Run the cases of ``todo`` with at most ``window`` at once until each is recorded."""
    spec, limit, timeout = study.spec, study.spec.executor.attempts, study.spec.executor.case_timeout_s
    fork_lanes = window < usable_cores()     # fewer workers than cores: a forked lane has a core to use
    suspects: deque[tuple[Case, int]] = deque()
    running: dict[Future, _Running] = {}

    def submit(case: Case, attempts: int):
        pool = local.executor if local else executor
        future = pool.submit(run_case, spec.command, case.problem, _case_source(spec, case), fork_lanes)
        running[future] = _Running(case, attempts, time.monotonic())

    def died(lost: list[_Running], message: str):
        for item in lost:
            if item.attempts + 1 >= limit:
                study.record(item.case, {"status": CRASHED, "error": message}, item.attempts + 1)
            else:
                suspects.append((item.case, item.attempts + 1))

    try:
        while todo or suspects or running:
            if suspects and not running:
                submit(*suspects.popleft())
            alone = any(item.attempts for item in running.values())    # a case whose worker died runs alone
            while todo and not suspects and not alone and len(running) < window:
                submit(todo.popleft(), 0)
            done, _ = wait(list(running), timeout=TICK_S, return_when=FIRST_COMPLETED)
            broken = False
            for future in done:
                error = future.exception()
                if isinstance(error, BrokenExecutor):
                    broken = True
                    continue
                item = running.pop(future)
                if error is not None:       # the cluster gave the case up (a worker died with it each time)
                    study.record(item.case, {"status": CRASHED, "error": f"{type(error).__name__}: {error}"},
                                 item.attempts + 1)
                else:
                    study.record(item.case, future.result(), item.attempts + 1)
            if broken:
                if not local:
                    raise TransplanterError("the executor broke (a worker died); the finished cases are kept, and "
                                            "--resume runs the others")
                lost = list(running.values())
                running.clear()
                local.restart()
                died(lost, "the worker running it died")
                continue
            now = time.monotonic()
            late = [f for f, item in running.items() if timeout and now - item.submitted > timeout]
            for future in late:
                item = running.pop(future)
                future.cancel()
                study.record(item.case, {"status": TIMEOUT, "error": f"ran past executor.case_timeout_s = "
                                                                     f"{timeout:g} s"}, item.attempts + 1)
            if late and local:          # the late cases still hold their workers: new workers, the others again
                for item in running.values():
                    todo.appendleft(item.case)
                running.clear()
                local.restart()
    except BaseException:
        for future in running:
            future.cancel()
        raise


def run(spec: StudySpec, out: str | Path, executor: Any = None, resume: bool = False,
        on_case: Callable[[dict], None] | None = None, show_progress: bool = False) -> StudyOutcome:
    """Run every case of ``spec`` (or with ``resume``, those that ``out``'s table lacks) and write the results
    into ``out`` as they finish, then the report and the figures.

    Parameters
    ----------
    spec : StudySpec
        From ``load_study`` or ``parse_study``.
    out : str or Path
        The study's folder: new, empty, or of this study (``resume``).
    executor : concurrent.futures.Executor or distributed.Client, optional
        Where the cases run; by default local worker processes (``[executor] workers``, or one per core), or the
        Dask cluster at ``[executor] scheduler``.
    resume : bool
        Continue a study whose folder already holds some of its cases.
    on_case : callable, optional
        Called with each case's table row as it is recorded.
    show_progress : bool
        A progress bar on stderr.

    Raises
    ------
    ProblemError
        Bad input (a case the command refuses, an unreachable scheduler, a folder of something else), before any
        case runs.
    """
    cases = study_cases(spec)
    _check_cases(spec, cases)
    client = dask_client(spec.executor.scheduler) if executor is None and spec.executor.scheduler else None
    try:
        folder = prepare_folder(out, spec, resume)
        header = columns(spec.fields, spec.collect)
        finished = {row["case_id"] for row in read_rows(folder / "cases.csv", header)}
        todo = deque(case for case in cases if case.case_id not in finished)
        local = LocalWorkers(spec.executor.workers) if executor is None and client is None else None
        pool, window = as_executor(client if client is not None else executor) if local is None \
            else (local.executor, local.workers)
        with ProgressBar(len(cases), len(cases) - len(todo), show_progress) as bar:
            study = _Study(spec, folder, bar, on_case)
            try:
                _loop(study, todo, pool, window, local)
            finally:
                if local:
                    local.stop()
        rows = read_rows(folder / "cases.csv", header)
        write_summary(spec, folder, rows)
        return StudyOutcome(folder, rows, study.ran)
    finally:
        if client is not None:
            client.close()


"""One case, run in a worker: the design command's own job on the case's problem, as ``transplanter <command>``
runs it, reduced to what the study records.

The solvers a job builds (CasADi Functions, which do not pickle) are built in the worker from the problem data
and kept there by the mechanisms' own caches, so the worker's next case reuses them.

A five-bar job refines its candidates in two lanes, the second in a forked process (``fivebar.lanes``); where a
study runs as many cases at once as there are cores, the workers are the parallelism and a fork per case would
oversubscribe the cores: the case then runs both lanes in its worker (the same outcome).
"""
from __future__ import annotations

import contextlib
import time
import warnings
from typing import Any

from transplanter.errors import TransplanterError
from transplanter.fivebar.lanes import lanes_here
from transplanter.study.binding import binding_requirement
from transplanter.study.worker_memory import case_memory

#: The statuses of a case, by the exit class of the command (0, 1, 2) or by what stopped it.
PASSED, FAILED, NO_RESULT, ERROR, TIMEOUT, CRASHED = "passed", "failed", "no result", "error", "timeout", "crashed"


def one_line(text: object) -> str:
    """``text`` on one line (an error as the study table records it)."""
    return " ".join(str(text).split())


def run_case(command_name: str, problem: dict, source: str, fork_lanes: bool = True) -> dict[str, Any]:
    """Run ``command_name`` on ``problem`` (the problem file's content) as the command line does, without
    figures or files (``fork_lanes`` False: a five-bar's lanes both in this process): the case's status, the
    command's exit class (0 passed, 1 failed a check, 2 no result; None for an error the command does not
    expect, a bug), its one-line error, the requirement that binds, the seconds it took, its report (report.json's
    content) and the worker's memory over the case (``worker_memory.case_memory``, taken once the job's objects
    are gone). Errors are recorded without the ``source`` they start with."""
    with case_memory() as memory:
        outcome = _job_outcome(command_name, problem, source, fork_lanes)
    return {**outcome, "memory": memory}


def _job_outcome(command_name: str, problem: dict, source: str, fork_lanes: bool) -> dict[str, Any]:
    """``run_case``'s outcome but the memory."""
    from transplanter.cli import COMMANDS, command_defaults

    command = next(c for c in COMMANDS if c.name == command_name)
    start = time.perf_counter()
    report: dict[str, Any] = {}
    with warnings.catch_warnings(record=True) as warned, contextlib.nullcontext() if fork_lanes else lanes_here():
        warnings.simplefilter("always")
        try:
            result = command.run(command, command.package.parse_problem(problem, source),
                                 command_defaults(command_name, source))
        except TransplanterError as error:
            status, exit_class, message = NO_RESULT, 2, one_line(str(error).removeprefix(f"{source}: "))
        except Exception as error:      # a bug of the job: recorded, and the study goes on
            status, exit_class, message = ERROR, None, one_line(f"{type(error).__name__}: {error}")
        else:
            report = result.to_json()
            failures = list(result.failures)
            if result.passed:
                status, exit_class, message = PASSED, 0, ""
            else:
                status, exit_class = (FAILED, 1) if result.produced else (NO_RESULT, 2)
                message = one_line("failed: " + "; ".join(failures))
                report = {"status": "FAILED", "failures": failures, **report}
    return {"status": status, "exit_class": exit_class, "error": message,
            "binding": binding_requirement(message, problem) if message else "",
            "seconds": time.perf_counter() - start, "report": report,
            "warnings": [one_line(w.message) for w in warned]}

"""Where a case's five-bar lanes run: in its worker when the study runs as many cases at once as there are
cores (the workers are the parallelism), the second lane forked when a core is left for it."""
from __future__ import annotations

import dataclasses
from concurrent.futures import ThreadPoolExecutor

import pytest

from tests.study.studies import gear_study
from transplanter import cli
from transplanter.cores import usable_cores
from transplanter.errors import TransplanterError
from transplanter.fivebar import lanes
from transplanter.study import run, runner, study_cases
from transplanter.study.case_run import run_case


def test_a_case_told_not_to_fork_runs_within_lanes_here_and_only_that_case(monkeypatch):
    seen = []
    gear = next(command for command in cli.COMMANDS if command.name == "gear")

    def job(command, problem, args):
        seen.append(lanes._may_fork.get())
        raise TransplanterError("seen")

    monkeypatch.setattr(cli, "COMMANDS", [dataclasses.replace(gear, run=job)])
    problem = study_cases(gear_study())[0].problem
    outcomes = [run_case("gear", problem, "case", fork_lanes=fork) for fork in (False, True)]
    assert seen == [False, True] and lanes._may_fork.get()
    assert [outcome["error"] for outcome in outcomes] == ["seen", "seen"]


@pytest.mark.parametrize("extra, forks", [(0, False), (-1, True)])
def test_the_study_forks_lanes_only_with_fewer_cases_at_once_than_cores(monkeypatch, tmp_path, extra, forks):
    """An executor as wide as this machine's cores (``extra`` 0) gets cases told not to fork; a narrower one
    (one fewer, where the machine has more than one core) gets cases told to."""
    cores = usable_cores()
    if cores + extra < 1:
        pytest.skip("one core: no narrower executor")
    told = []

    def recorded(command_name, problem, source, fork_lanes=True):
        told.append(fork_lanes)
        return {"status": "no result", "exit_class": 2, "error": "recorded", "binding": "", "seconds": 0.0,
                "report": {}, "warnings": []}

    monkeypatch.setattr(runner, "run_case", recorded)
    with ThreadPoolExecutor(cores + extra) as executor:
        run(gear_study(), tmp_path / "out", executor=executor)
    assert told == [forks] * 4

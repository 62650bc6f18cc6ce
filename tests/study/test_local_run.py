"""Studies on local worker processes: every case as the command runs it, nothing lost when a study is stopped
or a worker dies, timeouts and failures recorded with their class."""
from __future__ import annotations

import json
import multiprocessing
import os
import signal
from concurrent.futures import ThreadPoolExecutor

import pytest

from tests.study.studies import gear_study, same_tables
from transplanter import gears
from transplanter.errors import ProblemError, TransplanterError
from transplanter.study import run, study_cases
from transplanter.study.case_run import run_case


@pytest.fixture(scope="module")
def finished(tmp_path_factory):
    """The gear study run whole on two local workers, with a Pareto front of two objectives."""
    out = tmp_path_factory.mktemp("study") / "out"
    return run(gear_study(objectives=[{"quantity": "center_distance", "goal": "min"},
                                      {"quantity": "ratio_range.1", "goal": "max"}]), out)


def test_each_case_is_the_commands_own_result(finished):
    cases = {case.case_id: case for case in study_cases(gear_study())}
    assert sorted(row["case_id"] for row in finished.rows) == sorted(cases)
    for row in finished.rows:
        case = cases[row["case_id"]]
        try:
            result = gears.synthesize(gears.parse_problem(case.problem, "case"))
        except TransplanterError as error:   # the undercut the command reports with exit 2
            assert (row["status"], row["exit_class"]) == ("no result", "2")
            assert row["error"] == str(error).removeprefix("case: ") and "undercuts" in row["error"]
            assert row["binding"] == "pair.teeth" and row["center_distance"] == ""
            continue
        assert (row["status"], row["exit_class"]) == ("passed", "0") if result.passed else ("failed", "1")
        assert row["error"] == ("" if result.passed else "failed: " + "; ".join(result.failures))
        assert float(row["center_distance"]) == result.to_json()["center_distance"]
        assert float(row["ratio_range.1"]) == result.to_json()["ratio_range"][1]
        report = json.loads((finished.folder / "cases" / row["case_id"] / "report.json").read_text())
        assert report["values"] == case.values and report["report"]["center_distance"] == result.to_json()[
            "center_distance"]
        memory = report["worker_memory"]        # a worker's, taken in it
        assert memory["pid"] != os.getpid() and memory["peak_mb"] >= memory["resident_mb"] > 0
    assert {row["status"] for row in finished.rows} == {"passed", "failed", "no result"}


def test_the_summary_lists_every_file_and_the_failure_classes(finished):
    report = json.loads((finished.folder / "report.json").read_text())
    listed = {name for names in report["files"].values() for name in names}
    assert listed == {path.name for path in finished.folder.iterdir() if path.is_file()}
    assert {"feasibility.png", "quantities.png", "pareto.png", "cases.csv", "report.md"} <= listed
    passed = {row["case_id"] for row in finished.rows if row["status"] == "passed"}
    assert report["best_cases"] and set(report["best_cases"]) <= passed
    undercut = [row for row in finished.rows if row["status"] == "no result"]
    assert {"status": "no result", "exit_class": 2, "binding": "pair.teeth", "cases": len(undercut),
            "example_error": undercut[-1]["error"]} in report["failure_classes"]
    assert sum(c["cases"] for c in report["failure_classes"]) == sum(r["status"] != "passed" for r in finished.rows)
    assert "## Failure classes" in (finished.folder / "report.md").read_text()


def test_a_stopped_study_resumes_with_no_case_run_twice_and_the_same_table(finished, tmp_path):
    out = tmp_path / "out"

    def stop_after_two(row, seen=[]):       # noqa: B006 (counts the rows of this one run)
        seen.append(row)
        if len(seen) == 2:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run(gear_study(), out, on_case=stop_after_two)
    first = (out / "cases.csv").read_text().splitlines()
    assert len(first) == 3
    with pytest.raises(ProblemError, match="holds results of this study; expected --resume"):
        run(gear_study(), out)
    resumed = run(gear_study(), out, resume=True)
    assert resumed.ran == 2 and (out / "cases.csv").read_text().splitlines()[:3] == first
    assert same_tables(resumed.rows, finished.rows)


def test_a_folder_of_another_study_is_refused(finished):
    other = gear_study(vary=[{"field": "driver.eccentricity", "values": [0.3]}])
    with pytest.raises(ProblemError, match="holds the results of another study"):
        run(other, finished.folder, resume=True)


def test_a_worker_killed_mid_study_leaves_every_case_recorded_once(finished, tmp_path):
    killed = []

    def kill_a_worker(row):
        if not killed:
            worker = multiprocessing.active_children()[0]
            os.kill(worker.pid, signal.SIGKILL)
            killed.append(worker.pid)

    outcome = run(gear_study(), tmp_path / "out", on_case=kill_a_worker)
    assert killed and same_tables(outcome.rows, finished.rows)
    assert max(int(row["attempts"]) for row in outcome.rows) <= 2


def test_a_case_past_its_timeout_is_recorded_as_one(tmp_path):
    spec = gear_study(vary=[{"field": "pair.teeth", "values": [30, 40]}], executor={"case_timeout_s": 0.05})
    outcome = run(spec, tmp_path / "out")
    assert [row["status"] for row in outcome.rows] == ["timeout", "timeout"]
    assert all("executor.case_timeout_s = 0.05 s" in row["error"] for row in outcome.rows)
    assert outcome.unfinished == outcome.rows


def test_any_executor_runs_the_same_cases(finished, tmp_path):
    with ThreadPoolExecutor(1) as executor:
        outcome = run(gear_study(), tmp_path / "out", executor=executor)
    assert same_tables(outcome.rows, finished.rows)


def test_a_bug_of_a_job_is_recorded_as_an_error_with_its_type():
    outcome = run_case("gear", {"driver": "not a table"}, "case")
    assert outcome["exit_class"] == 2 and outcome["status"] == "no result" and outcome["error"].startswith("driver")

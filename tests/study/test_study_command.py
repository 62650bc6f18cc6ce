"""``transplanter study``: exit codes, one line for bad input, Ctrl-C keeps the finished cases, --resume."""
from __future__ import annotations

import contextlib
import csv
import signal
import subprocess
import sys
import time
import tomllib
from pathlib import Path

import pytest

from tests.study.studies import EXAMPLES, gear_study_data
from transplanter.cli import main
from transplanter.study.binding import binding_requirement


def _write_study(folder: Path, **changes) -> Path:
    def toml_value(value):
        if isinstance(value, str):
            return '"' + value + '"'
        if isinstance(value, list):
            return "[" + ", ".join(toml_value(v) for v in value) + "]"
        if isinstance(value, dict):
            return "{" + ", ".join(f"{k} = {toml_value(v)}" for k, v in value.items()) + "}"
        return repr(value)

    data = gear_study_data(**changes)
    lines = [f"{key} = {toml_value(value)}" for key, value in data.items() if key not in ("vary", "executor")]
    lines += [f"vary = {toml_value(data['vary'])}", "[executor]",
              *(f"{k} = {toml_value(v)}" for k, v in data["executor"].items())]
    path = folder / "study.toml"
    path.write_text("\n".join(lines) + "\n")
    assert tomllib.loads(path.read_text()) == data
    return path


def _ids(out: Path) -> list[str]:
    with (out / "cases.csv").open() as stream:
        return [row["case_id"] for row in csv.DictReader(stream)]


def test_ctrl_c_exits_130_keeping_the_finished_cases_and_resume_runs_only_the_rest(tmp_path):
    study, out = _write_study(tmp_path, vary=[{"field": "pair.teeth", "range": [30, 80], "step": 10}]), tmp_path / "o"
    command = [sys.executable, "-m", "transplanter", "study", str(study), "--out", str(out)]
    process = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    while process.poll() is None and not ((out / "cases.csv").exists() and _ids(out)):
        time.sleep(0.05)
    process.send_signal(signal.SIGINT)
    _, error = process.communicate(timeout=60)
    kept = _ids(out)
    assert process.returncode == 130 and error.splitlines() == ["transplanter: interrupted"]
    assert 1 <= len(kept) < 6
    resumed = subprocess.run([*command, "--resume"], capture_output=True, text=True, timeout=300)
    assert resumed.returncode == 0, resumed.stderr
    assert f"6 cases ({6 - len(kept)} run now)" in resumed.stdout
    ids = _ids(out)
    assert ids[:len(kept)] == kept and sorted(set(ids)) == sorted(ids) and len(ids) == 6


@pytest.mark.parametrize("arguments, expected", [
    (["--scheduler", "tcp://127.0.0.1:9"], "unreachable"),
    (["--scheduler", "localhost"], "--scheduler = localhost: expected a Dask scheduler address"),
])
def test_bad_input_is_one_line_and_exit_2_before_any_case_runs(tmp_path, capsys, arguments, expected):
    study = _write_study(tmp_path)
    assert main(["study", str(study), "--out", str(tmp_path / "o"), *arguments]) == 2
    error = capsys.readouterr().err
    assert len(error.splitlines()) == 1 and expected in error
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("message, binding", [
    ("no 2R chain B-E survives: ranges.ep removes the last 3 of 40 traced dyads", "ranges.ep"),
    ("none of the 12 five-bars of the region is feasible (first failing condition per pair: crank: 9)",
     "none of the # five-bars of the region is feasible"),
    ("failed: a.b is not in the problem, so it is not a field", "a.b is not in the problem, so it is not a field"),
])
def test_the_binding_requirement_is_a_field_the_error_names_or_its_leading_phrase(message, binding):
    assert binding_requirement(message, {"ranges": {"ep": [1, 2]}}) == binding


def _children(pid: int) -> list[int]:
    return [int(c) for task in Path(f"/proc/{pid}/task").glob("*/children") for c in task.read_text().split()]


def _alive(pid: int) -> bool:
    """Whether ``pid`` runs (a zombie, dead but not yet reaped, does not)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] != "Z"
    except OSError:
        return False


@pytest.mark.skipif(not Path("/proc/self/task").exists(), reason="reads the process tree from /proc")
def test_ctrl_c_during_a_five_bar_case_ends_its_worker_and_the_workers_forked_lane(tmp_path):
    study = tmp_path / "study.toml"
    study.write_text(f'command = "fivebar"\nproblem = "{EXAMPLES / "vegetable_planting.toml"}"\n'
                     '[[vary]]\nfield = "key_poses.2.angle_deg"\nvalues = [90.0]\n[executor]\nworkers = 1\n')
    process = subprocess.Popen([sys.executable, "-m", "transplanter", "study", str(study), "--out",
                                str(tmp_path / "o")], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    workers: list[int] = []
    lanes: list[int] = []
    while process.poll() is None and not lanes:
        time.sleep(0.1)
        with contextlib.suppress(OSError):      # a process that ended meanwhile
            workers = [pid for pid in _children(process.pid)
                       if "spawn_main" in Path(f"/proc/{pid}/cmdline").read_text()]
            lanes = [lane for worker in workers for lane in _children(worker)]
    process.send_signal(signal.SIGINT)
    _, error = process.communicate(timeout=60)
    assert lanes and process.returncode == 130 and error.splitlines() == ["transplanter: interrupted"]
    assert not any(_alive(pid) for pid in [*workers, *lanes])

"""A command's figures shared between a side process and the process writing its files: the same files and bytes
as in turn, ``--plot`` as before, a figure's error the same one line and exit code, Ctrl-C ending both."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from transplanter import side_process
from transplanter.burmester.result import Synthesis
from transplanter.cli import main
from transplanter.errors import TransplanterError

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = str(ROOT / "examples" / "burmester_3poses.toml")


@pytest.fixture
def two_cores(monkeypatch):
    """As on a machine that gives this process two cores, whatever runs the test."""
    monkeypatch.setattr(side_process, "usable_cores", lambda: 2)


def _run(folder: Path) -> dict[str, bytes]:
    out, plot = folder / "out", folder / "plot.png"
    assert main(["burmester", PROBLEM, "--out", str(out), "--plot", str(plot), "--quiet"]) == 0
    written = {path.name: path.read_bytes() for path in out.iterdir()}
    report = json.loads(written.pop("report.json"))
    assert sorted(name for names in report["files"].values() for name in names) == sorted([*written, "report.json"])
    assert sorted(os.listdir(folder)) == ["out", "plot.png"]       # nothing left beside them
    return {**written, "--plot": plot.read_bytes()}


def test_figures_shared_with_a_side_process_are_the_files_drawn_here(tmp_path, monkeypatch, two_cores):
    beside = _run(tmp_path / "beside")
    monkeypatch.setattr(side_process, "FORKS", False)
    here = _run(tmp_path / "here")
    assert beside.keys() == here.keys() and "burmester.png" in beside
    assert [name for name in beside if beside[name] != here[name]] == []


@pytest.mark.parametrize("forks", [True, False], ids=["beside", "here"])
def test_an_error_drawing_a_figure_is_one_line_and_exit_2(tmp_path, monkeypatch, capsys, two_cores, forks):
    def broken():
        raise TransplanterError("the figure cannot be drawn")

    monkeypatch.setattr(Synthesis, "figure_drawers", lambda self: {"burmester": broken})
    if not forks:
        monkeypatch.setattr(side_process, "FORKS", False)
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out"), "--quiet"]) == 2
    assert capsys.readouterr().err == "transplanter: error: the figure cannot be drawn\n"
    assert os.listdir(tmp_path) == []


SLOW_FIGURES = """
import os, sys, time
from pathlib import Path
from transplanter import cli, side_process
from transplanter.burmester.result import Synthesis

side_process.usable_cores = lambda: 2
markers = Path(sys.argv[1])

def slow():
    (markers / str(os.getpid())).touch()
    time.sleep(60)

Synthesis.figure_drawers = lambda self: {f"slow{k}": slow for k in range(4)}
sys.argv = ["transplanter", "burmester", sys.argv[2], "--out", sys.argv[3]]
cli.console()
"""


def test_ctrl_c_while_the_figures_are_drawn_ends_both_processes_and_leaves_nothing(tmp_path):
    """Four slow figures: the side process takes the first, the run's own process the last once its files are
    written; Ctrl-C while both draw."""
    markers, out = tmp_path / "drawing", tmp_path / "out"
    markers.mkdir()
    run = subprocess.Popen([sys.executable, "-c", SLOW_FIGURES, str(markers), PROBLEM, str(out)], cwd=ROOT,
                           stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    deadline = time.monotonic() + 120
    while len(os.listdir(markers)) < 2 and run.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    drawing = sorted(int(name) for name in os.listdir(markers))
    assert len(drawing) == 2 and run.pid in drawing, run.communicate()[1]
    side = next(pid for pid in drawing if pid != run.pid)
    os.killpg(run.pid, signal.SIGINT)           # Ctrl-C reaches the whole process group
    _, err = run.communicate(timeout=30)
    assert run.returncode == 130
    assert err == f"transplanter: interrupted; {out} is left as it was\n"
    assert os.listdir(tmp_path) == ["drawing"]
    assert not Path(f"/proc/{side}").exists()

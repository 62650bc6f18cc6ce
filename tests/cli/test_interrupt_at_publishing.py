"""Interrupts at every step of putting the output in place, and around the end of a run: ``--out`` is always
either the earlier output or the new one, complete, never missing and never half written; nothing is left
beside it; the one stderr line says which of the two it holds; the exit code is 130."""
from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import transplanter.cli as cli
from transplanter import folder_swap
from transplanter.burmester.result import Synthesis
from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = str(ROOT / "examples" / "burmester_3poses.toml")


@pytest.fixture
def quick_runs(monkeypatch):
    """Runs without their figure (a third of a second each): the publishing is what is under test."""
    monkeypatch.setattr(Synthesis, "figure_drawers", lambda self: {})


def _earlier_output(out: Path) -> set[str]:
    """An earlier output of the command at ``out`` (its marker file is listed by its report.json)."""
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 0
    report = json.loads((out / "report.json").read_text())
    (out / "marker.csv").write_text("earlier\n")
    report["files"]["table"] = ["marker.csv"]
    (out / "report.json").write_text(json.dumps(report))
    return set(os.listdir(out))


def _whole_output(out: Path) -> str:
    """"earlier" or "new": which complete output ``out`` holds (every file its report.json lists, nothing else)."""
    report = json.loads((out / "report.json").read_text())
    listed = {name for names in report["files"].values() for name in names}
    assert set(os.listdir(out)) == listed, "a half-written output"
    return "earlier" if "marker.csv" in listed else "new"


def _renames_interrupted(monkeypatch, at: int, exchange: bool) -> list[str]:
    """Raise SIGINT in this process just before rename number ``at`` (0-based) of the publishing step; with
    ``exchange`` False the system is taken to have no atomic exchange (the two-rename fallback)."""
    calls: list[str] = []
    original_replace, original_exchange = Path.replace, folder_swap.exchange

    def interrupted(step, *arguments):
        if len(calls) == at:
            signal.raise_signal(signal.SIGINT)
        calls.append(step)

    def replace(self, target):
        if self.name.startswith(".") or self.parent.name.endswith(".partial"):   # the work folder's moves only
            interrupted("replace")
        return original_replace(self, target)

    def exchanging(first, second):
        interrupted("exchange")
        return original_exchange(first, second) if exchange else False
    monkeypatch.setattr(Path, "replace", replace)
    monkeypatch.setattr(folder_swap, "exchange", exchanging)
    return calls


@pytest.mark.parametrize("exchange", [True, False], ids=["exchange", "two renames"])
@pytest.mark.parametrize("at", [0, 1, 2])
def test_an_interrupt_at_each_rename_of_the_publishing_step(tmp_path, monkeypatch, capsys, quick_runs, exchange, at):
    out = tmp_path / "out"
    _earlier_output(out)
    capsys.readouterr()
    calls = _renames_interrupted(monkeypatch, at, exchange)
    code = main(["burmester", PROBLEM, "--out", str(out), "--quiet"])
    err = capsys.readouterr().err
    if at >= len(calls):            # the step had fewer renames: nothing interrupted it
        assert (code, err) == (0, "")
        return
    assert code == 130
    assert _whole_output(out) == "new"
    assert err == f"transplanter: interrupted after the run; {out} holds its new output, complete\n"
    assert os.listdir(tmp_path) == ["out"]


def test_with_no_earlier_output_an_interrupt_at_the_rename(tmp_path, monkeypatch, capsys, quick_runs):
    out = tmp_path / "out"
    _renames_interrupted(monkeypatch, 0, True)
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 130
    assert _whole_output(out) == "new" and os.listdir(tmp_path) == ["out"]


def test_interrupts_at_fifty_instants_around_the_end_of_a_run(tmp_path, monkeypatch, capsys, quick_runs):
    """SIGINT raised at the k-th Python call from the moment the result is published (reports written, the
    folder put in place, the work folder removed) until ``main`` gives the signal handlers back (a signal after
    that is the caller's), for 50 k spread over them: each run exits 130 saying which output ``--out`` holds,
    and that is what it holds."""
    out = tmp_path / "out"
    original = cli._publish
    calls = [0]
    instant = [0]

    def profile(frame, event, argument):
        if frame.f_code is signal.signal.__code__:      # the handlers are being given back
            sys.setprofile(None)
        elif event == "call":
            calls[0] += 1
            if calls[0] == instant[0]:
                signal.raise_signal(signal.SIGINT)

    def publish_profiled(*arguments):
        sys.setprofile(profile)
        return original(*arguments)

    def run() -> int:
        calls[0] = 0
        monkeypatch.setattr(cli, "_publish", publish_profiled)
        try:
            return main(["burmester", PROBLEM, "--out", str(out), "--quiet"])
        finally:
            sys.setprofile(None)
            monkeypatch.setattr(cli, "_publish", original)
    assert run() == 0
    total = calls[0]
    held = set()
    for k in np.unique(np.linspace(1, total, 50).round().astype(int)):
        _earlier_output(out)
        capsys.readouterr()
        instant[0] = int(k)
        code = run()
        err = capsys.readouterr().err
        holds = _whole_output(out)
        said = {"earlier": f"transplanter: interrupted; {out} is left as it was\n",
                "new": f"transplanter: interrupted after the run; {out} holds its new output, complete\n"}
        assert (code, err) == (130, said[holds]), (k, total)
        assert os.listdir(tmp_path) == ["out"], k
        held.add(holds)
    assert held == {"earlier", "new"}, "the instants reach past the step that puts the output in place"


def test_ctrl_c_twice_while_the_five_bar_refines_exits_130_promptly(tmp_path):
    """The forked refinement lane ignores Ctrl-C (its parent stops it) and a second Ctrl-C does not cut the
    clean-up short: the run ends with 130 within seconds, leaving nothing beside --out."""
    out = tmp_path / "out"
    process = subprocess.Popen([sys.executable, "-m", "transplanter", "fivebar", str(ROOT / "examples" /
                                "vegetable_planting.toml"), "--out", str(out), "--quiet"],
                               stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True, start_new_session=True)
    started = time.monotonic()
    while not any(tmp_path.glob(".out.*.partial")):  # the run's work folder: its handlers are in place
        assert process.poll() is None and time.monotonic() - started < 120, "the run did not start"
        time.sleep(0.1)
    time.sleep(3.0)                 # into the refinements, the second lane forked
    os.killpg(process.pid, signal.SIGINT)
    time.sleep(0.3)
    os.killpg(process.pid, signal.SIGINT)
    try:
        _, err = process.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        pytest.fail("the run did not end within 60 s of two Ctrl-C")
    assert process.returncode == 130, err
    assert err.strip().splitlines() == [f"transplanter: interrupted; {out} is left as it was"]
    assert os.listdir(tmp_path) == []

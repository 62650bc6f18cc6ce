"""Ctrl-C inside a library's C call: CasADi turns the KeyboardInterrupt its call raised into a SystemError (chained
from it). The run still ends as an interrupted run: exit 130, one line, --out left as it was."""
from __future__ import annotations

import signal
from pathlib import Path

from transplanter import burmester
from transplanter.cli import main

PROBLEM = str(Path(__file__).resolve().parents[2] / "examples" / "burmester_3poses.toml")


def _synthesize_interrupted_inside_c(problem):
    try:
        signal.raise_signal(signal.SIGINT)
    except KeyboardInterrupt as interrupt:
        raise SystemError("<built-in function DM_elements> returned a result with an exception set") from interrupt


def test_an_interrupt_a_library_turns_into_another_error(tmp_path, monkeypatch, capsys):
    out = tmp_path / "out"
    monkeypatch.setattr(burmester, "synthesize", _synthesize_interrupted_inside_c)
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 130
    assert capsys.readouterr().err == f"transplanter: interrupted; {out} is left as it was\n"
    assert list(tmp_path.iterdir()) == []            # no output, no work folder left


def test_the_same_error_without_an_interrupt_is_not_hidden(monkeypatch):
    """A SystemError with no interrupt behind it is a bug: it is not turned into an interrupted run."""
    def broken(problem):
        raise SystemError("a bug")
    monkeypatch.setattr(burmester, "synthesize", broken)
    try:
        main(["burmester", PROBLEM, "--quiet"])
    except SystemError as error:
        assert str(error) == "a bug"
    else:
        raise AssertionError("the SystemError was swallowed")

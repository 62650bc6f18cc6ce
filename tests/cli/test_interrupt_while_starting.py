"""Ctrl-C or SIGTERM while the program is still importing its modules (before the run's handler exists) ends it
with 130 and one line on stderr, never Python's KeyboardInterrupt traceback: the entry point handles both signals
from its first line on. The signal is raised by an import hook at the first import of a module on the way (the
command line itself, numpy deep inside it), so the moment is the same on every machine."""
from __future__ import annotations

import signal
import subprocess
import sys
from pathlib import Path

import pytest

PROBLEM = str(Path(__file__).resolve().parents[2] / "examples" / "burmester_3poses.toml")

#: Run in a fresh interpreter: a meta path finder that raises ``signal`` when ``module`` is first imported, then the
#: program as ``python -m transplanter`` runs it.
_PROGRAM = """
import signal, sys

class Interrupting:
    def find_spec(self, name, path=None, target=None):
        if name == {module!r}:
            sys.meta_path.remove(self)
            signal.raise_signal({signal})
        return None

sys.meta_path.insert(0, Interrupting())
sys.argv = ["transplanter", "burmester", {problem!r}, "--quiet"]
from transplanter.entry_point import console
console()
"""


@pytest.mark.parametrize("number", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
@pytest.mark.parametrize("module", ["transplanter.cli", "numpy"])
def test_a_signal_during_the_first_imports(module, number):
    code = _PROGRAM.format(module=module, signal=int(number), problem=PROBLEM)
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert run.returncode == 130
    assert run.stderr.count("\n") == 1 and "Traceback" not in run.stderr
    assert run.stderr.startswith("transplanter: interrupted") and run.stdout == ""

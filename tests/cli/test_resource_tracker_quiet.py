"""A process that made a semaphore and was killed leaves it to multiprocessing's resource tracker, which warns on
the program's stderr when the program ends; the program's entry keeps that off the run's one line of stderr."""
from __future__ import annotations

import subprocess
import sys

import pytest

# a child makes a semaphore and is killed before it can release it, as a study's worker is on Ctrl-C
SCRIPT = """
import multiprocessing, os, signal, sys
from transplanter.entry_point import quiet_resource_tracker

def killed_holding_a_semaphore():
    global held
    held = multiprocessing.get_context("spawn").Semaphore()
    os.kill(os.getpid(), signal.SIGKILL)

if __name__ == "__main__":
    if sys.argv[1] == "quiet":
        quiet_resource_tracker()
    context = multiprocessing.get_context("spawn")
    own = context.Semaphore()                       # the tracker starts here, with this process's warning options
    child = context.Process(target=killed_holding_a_semaphore)
    child.start()
    child.join()
    assert child.exitcode == -9
"""


@pytest.mark.parametrize("entry", ["quiet", "plain"])
def test_a_killed_workers_semaphore_is_removed_without_a_word_on_stderr(tmp_path, entry):
    script = tmp_path / "leak.py"
    script.write_text(SCRIPT)
    # stderr is read to its end: the tracker, which holds it too, has ended
    run = subprocess.run([sys.executable, str(script), entry], capture_output=True, text=True, timeout=60)
    assert run.returncode == 0, run.stderr
    if entry == "quiet":
        assert run.stderr == ""
    else:                                            # without the entry's option the tracker says so
        assert "resource_tracker: There appear to be 1 leaked semaphore" in run.stderr

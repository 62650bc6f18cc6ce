"""The side process: work beside this process where it may use a second core, in turn here where it may not
(one core, ``in_this_process``, a system that refuses the process); results, warnings and exceptions come back
as they were; an interrupt here ends it at once. Each is shown on one call in a side process beside work here
(``side_by_side`` below), the way ``shared_calls`` and ``twinned`` start and end theirs."""
from __future__ import annotations

import io
import multiprocessing
import os
import subprocess
import sys
import time
import warnings
from pathlib import Path

import pytest

from transplanter import progress, side_process
from transplanter.errors import SolverError
from transplanter.side_process import in_this_process, outcome, start_side_process

ROOT = Path(__file__).resolve().parents[2]


def side_by_side(there, here):
    """``there()`` in a side process while ``here()`` runs in this one (both here, in turn, where no side process
    may run); an exception of either raised here, the side process then stopped."""
    started = start_side_process(there, [()])
    if started is None:
        return there(), here()
    side, (future,) = started
    try:
        return_here = here()
        return_there = outcome(future)
    except BaseException:
        side.stop()
        raise
    side.close()
    return return_there, return_here


@pytest.fixture
def two_cores(monkeypatch):
    """As on a machine that gives this process two cores, whatever runs the test."""
    monkeypatch.setattr(side_process, "usable_cores", lambda: 2)


def ended_here(before: set) -> bool:
    """No process this test started is left (processes other tests left are not this test's)."""
    return set(multiprocessing.active_children()) <= before


def order_of_work():
    """Two pieces of work that record where and in which order they ran."""
    log: list[str] = []

    def there():
        log.append("there")         # in a side process: the side process's copy of the log
        return os.getpid(), list(log)

    def here():
        log.append("here")
        return os.getpid(), list(log)

    return there, here


def test_the_side_runs_in_another_process_beside_this_one(two_cores):
    before = set(multiprocessing.active_children())
    there, here = order_of_work()
    (there_pid, there_log), (here_pid, here_log) = side_by_side(there, here)
    assert here_pid == os.getpid() and there_pid != os.getpid()
    assert there_log == ["there"] and here_log == ["here"]      # each saw only its own work
    assert ended_here(before)           # the side process has ended


@pytest.mark.parametrize("confined", ["one core", "in this process", "not Linux", "refused"])
def test_where_no_side_process_may_run_both_run_here_the_side_first(monkeypatch, confined):
    monkeypatch.setattr(side_process, "usable_cores", lambda: 1 if confined == "one core" else 2)
    if confined == "not Linux":
        monkeypatch.setattr(side_process, "FORKS", False)
    if confined == "refused":       # a sandbox without semaphores or fork
        def refused(*args, **kwargs):
            raise OSError(38, "Function not implemented")
        monkeypatch.setattr(side_process, "ProcessPoolExecutor", refused)
    there, here = order_of_work()
    with in_this_process() if confined == "in this process" else warnings.catch_warnings():
        (there_pid, there_log), (here_pid, here_log) = side_by_side(there, here)
    assert there_pid == here_pid == os.getpid()
    assert there_log == ["there"] and here_log == ["there", "here"]
    assert side_process._may_fork.get()


def test_the_cores_are_the_ones_this_process_may_use():
    """A process confined to one core (as by ``taskset -c 0``) runs the side here, one given two forks it."""
    cores = sorted(os.sched_getaffinity(0))
    if len(cores) < 2:
        pytest.skip("this process has one core: no second to give")
    script = ("import os, sys\nfrom transplanter.side_process import may_fork\n"
              "from tests.cli.test_side_process import side_by_side\n"
              "os.sched_setaffinity(0, {int(c) for c in sys.argv[1:]})\n"
              "there, here = side_by_side(os.getpid, os.getpid)\n"
              "print(may_fork(), there == here)\n")
    seen = [subprocess.run([sys.executable, "-c", script, *map(str, given)], capture_output=True, text=True,
                           check=True, cwd=ROOT).stdout.split() for given in (cores[:1], cores[:2])]
    assert seen == [["False", "True"], ["True", "False"]]


def test_an_exception_of_the_side_is_raised_here_as_itself(two_cores):
    """Its class, message and state, even where its constructor takes other arguments than its message."""
    def there():
        raise SolverError("the design NLP did not converge", "Maximum_Iterations_Exceeded")

    before = set(multiprocessing.active_children())
    with pytest.raises(SolverError, match="did not converge") as raised:
        side_by_side(there, lambda: None)
    assert raised.value.status == "Maximum_Iterations_Exceeded"
    assert str(raised.value) == "the design NLP did not converge (solver status: Maximum_Iterations_Exceeded)"
    assert ended_here(before)


def test_an_oserror_of_the_side_keeps_its_file_name(two_cores):
    def there():
        return open("/nonexistent/folder/figure.png", "wb")

    with pytest.raises(FileNotFoundError) as raised:
        side_by_side(there, lambda: None)
    assert raised.value.filename == "/nonexistent/folder/figure.png" and raised.value.strerror


def test_warnings_of_the_side_are_raised_here(two_cores):
    def there():
        warnings.warn("a figure that cannot be laid out", UserWarning, stacklevel=1)
        return os.getpid()

    with warnings.catch_warnings(record=True) as log:
        warnings.simplefilter("always")
        pid, _ = side_by_side(there, lambda: None)
    assert pid != os.getpid()
    assert [(str(w.message), w.category) for w in log] == [("a figure that cannot be laid out", UserWarning)]


def test_an_interrupt_here_ends_the_side_at_once(two_cores):
    """Ctrl-C while this process does its part: the side process (5 s of work here) is ended, not waited for."""
    def here():
        time.sleep(0.3)
        raise KeyboardInterrupt

    before = set(multiprocessing.active_children())
    start = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        side_by_side(lambda: time.sleep(5.0), here)
    assert time.perf_counter() - start < 2.0
    assert ended_here(before)


def test_progress_lines_of_the_side_are_shown_here_and_silent_where_progress_is(two_cores):
    def there():
        progress.report("figures", 1, 2)
        return os.getpid()

    shown = io.StringIO()
    with progress.showing(shown):
        pid, _ = side_by_side(there, lambda: progress.report("files", 1, 1))
    assert pid != os.getpid()
    assert shown.getvalue() == "transplanter: files 1/1\ntransplanter: figures 1/2\n"
    with progress.showing(shown, enabled=False):
        side_by_side(there, lambda: None)
    assert shown.getvalue().count("\n") == 2


def test_a_side_process_killed_from_outside_gives_one_clear_error(two_cores):
    """Not the pool's BrokenProcessPool (the CLI would print a traceback): the run's own error, in words."""
    from transplanter.errors import TransplanterError

    def killed():
        os.kill(os.getpid(), 9)

    before = set(multiprocessing.active_children())
    with pytest.raises(TransplanterError, match="ended before it gave its result") as raised:
        side_by_side(killed, lambda: None)
    assert "\n" not in str(raised.value)
    assert ended_here(before)


def test_side_processes_stopped_one_after_another_leave_nothing_that_holds_the_next():
    """A side process stopped on an error, then the next forked at once, forty times: each ends, none waits for ever
    on a lock a thread of the one before held at the fork (it did, 2 runs in 3, before the stop joined that
    thread). In a child Python with a time limit, so a hang fails the test instead of holding the suite."""
    if len(os.sched_getaffinity(0)) < 2:
        pytest.skip("this process has one core: no side process")
    script = ("import multiprocessing\nfrom tests.cli.test_side_process import side_by_side\n"
              "def there():\n    raise ValueError('stop')\n"
              "left = 0\nfor _ in range(40):\n    try:\n        side_by_side(there, lambda: None)\n"
              "    except ValueError:\n        pass\n    left += len(multiprocessing.active_children())\nprint(left)\n")
    child = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, check=True,
                           cwd=ROOT)
    assert child.stdout.split() == ["0"]


def test_a_side_process_stopped_as_it_starts_runs_none_of_this_process_signal_handling():
    """Started and at once stopped, forty times, in a process whose SIGTERM handler raises (as the command line's
    stops a run): no side process runs that handler. It did, printing its traceback, in about one start of four;
    raised just after the fork, it sent the copy back into the code of the process that forked it, where one test
    run waited for ever. In a child Python with a time limit, so a hang fails the test instead of holding the
    suite."""
    if len(os.sched_getaffinity(0)) < 2:
        pytest.skip("this process has one core: no side process")
    script = ("import os, signal\nfrom transplanter.side_process import start_side_process\n"
              "def stopping(signum, frame):\n    raise RuntimeError('the handler of the process that forked')\n"
              "signal.signal(signal.SIGTERM, stopping)\nme = os.getpid()\n"
              "for _ in range(40):\n    side, _ = start_side_process(lambda: None, [()])\n    side.stop()\n"
              "    assert os.getpid() == me\nprint('done')\n")
    child = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120, cwd=ROOT)
    assert (child.returncode, child.stdout, child.stderr) == (0, "done\n", "")

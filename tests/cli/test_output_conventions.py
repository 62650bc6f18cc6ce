"""The command line's output conventions: --out written whole or not at all, report.json lists its files,
progress on stderr unless --quiet or --json, FAILED results exit 1."""
import contextlib
import io
import json
import os
import sys
from pathlib import Path

import pytest
from matplotlib.figure import Figure

from transplanter import burmester, folder_swap
from transplanter.cli import main
from transplanter.errors import ProblemError
from transplanter.output_folder import files_by_kind

PROBLEM = str(Path(__file__).resolve().parents[2] / "examples/burmester_4poses.toml")


@pytest.fixture(autouse=True)
def small_figures(monkeypatch):
    """One small figure instead of the real ones: these tests are about the files, not the pictures."""
    def draw():
        fig = Figure(figsize=(1, 1))
        fig.subplots().plot([0, 1])
        return fig
    monkeypatch.setattr(burmester.Synthesis, "figure_drawers", lambda result: {"burmester": draw})


def _listed(folder: Path) -> set[str]:
    report = json.loads((folder / "report.json").read_text())
    return {name for names in report["files"].values() for name in names}


def test_report_json_lists_exactly_the_files_of_the_run(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 0
    assert _listed(out) == {p.name for p in out.iterdir()} == {"report.json", "report.md", "burmester.png"}
    assert json.loads((out / "report.json").read_text())["files"]["figure"] == ["burmester.png"]
    assert [p.name for p in tmp_path.iterdir()] == ["out"]            # nothing left beside it


def test_files_are_grouped_by_kind():
    assert files_by_kind(["b.csv", "a.dxf", "x.gif", "r.md", "a.svg", "n.xyz"]) == {
        "table": ["b.csv"], "drawing": ["a.dxf", "a.svg"], "animation": ["x.gif"], "report": ["r.md"],
        "other": ["n.xyz"]}


def _break_figures(monkeypatch):
    """The run writes a file into the folder, then fails."""
    import transplanter.cli as cli
    original = cli._save_figure

    def save_then_fail(figure, path, dpi):
        original(Figure(figsize=(1, 1)), path.with_name("half.png"), dpi)
        raise ProblemError("figures: made to fail")
    monkeypatch.setattr(cli, "_save_figure", save_then_fail)


def test_a_failing_run_leaves_no_half_folder(tmp_path, monkeypatch, capsys):
    _break_figures(monkeypatch)
    out = tmp_path / "out"
    assert main(["burmester", PROBLEM, "--out", str(out)]) == 2
    assert capsys.readouterr().err.strip().splitlines()[-1] == "transplanter: error: figures: made to fail"
    assert list(tmp_path.iterdir()) == []


def test_sigterm_ends_a_run_as_ctrl_c_does(tmp_path, monkeypatch, capsys):
    """A timeout's SIGTERM in the middle of the work: exit 130, no half folder beside the target, and the
    process's own SIGTERM handler given back afterwards."""
    import signal

    import transplanter.cli as cli
    original = cli._save_figure

    run = os.getpid()       # the run's process (the figures may be saved in a side process of it)

    def save_then_terminate(figure, path, dpi):
        original(figure, path, dpi)
        os.kill(run, signal.SIGTERM)
    monkeypatch.setattr(cli, "_save_figure", save_then_terminate)
    before = signal.getsignal(signal.SIGTERM)
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out"), "--quiet"]) == 130
    assert capsys.readouterr().err.strip() == f"transplanter: interrupted; {tmp_path / 'out'} is left as it was"
    assert list(tmp_path.iterdir()) == [] and signal.getsignal(signal.SIGTERM) is before


@pytest.mark.parametrize("signal_name", ["SIGTERM", "SIGINT"])
def test_an_interrupt_a_solver_swallows_still_ends_the_run(tmp_path, monkeypatch, capsys, signal_name):
    """IPOPT's callbacks catch the KeyboardInterrupt a signal raises inside a solve, report it as a warning of
    their own and return a failed solve, and the work goes on: the run still exits 130, writes nothing, and the
    only stderr line is its own (it exited 0 and replaced --out, with CasADi's warning on stderr). Both
    handlers are given back."""
    import signal
    number = getattr(signal, signal_name)
    original = burmester.synthesize

    def solve_swallowing_the_interrupt(problem):
        try:
            os.kill(os.getpid(), number)
        except KeyboardInterrupt:
            sys.stderr.write('CasADi - WARNING("KeyboardInterruptException")\n')
        return original(problem)
    monkeypatch.setattr(burmester, "synthesize", solve_swallowing_the_interrupt)
    before = {n: signal.getsignal(n) for n in (signal.SIGINT, signal.SIGTERM)}
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out"), "--quiet"]) == 130
    assert capsys.readouterr().err == f"transplanter: interrupted; {tmp_path / 'out'} is left as it was\n"
    assert list(tmp_path.iterdir()) == []
    assert {n: signal.getsignal(n) for n in before} == before


def test_an_error_the_interrupt_caused_ends_the_run_as_interrupted(tmp_path, monkeypatch, capsys):
    """SIGTERM to the whole process group ends a side process too, and the run then meets the side's error: the
    interrupt came first, so the run exits 130 as interrupted, not 2 with that error."""
    import signal

    from transplanter.errors import TransplanterError

    def solve_then_lose_the_side(problem):
        with contextlib.suppress(KeyboardInterrupt):   # as a solver swallows it (above); the side ended meanwhile
            os.kill(os.getpid(), signal.SIGTERM)
        raise TransplanterError("a side process of this run ended before it gave its result")
    monkeypatch.setattr(burmester, "synthesize", solve_then_lose_the_side)
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out"), "--quiet"]) == 130
    assert capsys.readouterr().err == f"transplanter: interrupted; {tmp_path / 'out'} is left as it was\n"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("exchange", [True, False], ids=["exchange", "two renames"])
def test_an_out_that_cannot_be_replaced_names_it_and_leaves_nothing_beside_it(tmp_path, monkeypatch, capsys, exchange):
    """The finished folder cannot be moved into place (an immutable folder, as chattr +i makes, refused even to
    root), by an atomic exchange or, where the system has none, by two renames: one line naming --out, and the
    hidden partial copy removed (it was left beside the target)."""
    out = tmp_path / "out"
    out.mkdir()
    original = Path.replace

    def refuse_the_target(self, target):
        if out in (self, Path(target)):        # neither moved away nor replaced
            raise PermissionError(1, "Operation not permitted")
        return original(self, target)

    def refuse_the_exchange(first, second):
        if not exchange:
            return False
        raise PermissionError(1, "Operation not permitted")
    monkeypatch.setattr(Path, "replace", refuse_the_target)
    monkeypatch.setattr(folder_swap, "exchange", refuse_the_exchange)
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"transplanter: error: --out = {out}: cannot put the results there (Operation not permitted): "
                   "expected a folder this user can replace; it is left as it was")
    assert [p.name for p in tmp_path.iterdir()] == ["out"] and list(out.iterdir()) == []


def test_an_earlier_output_survives_a_failing_run_and_is_replaced_by_a_good_one(tmp_path, monkeypatch):
    out = tmp_path / "out"
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 0
    earlier = {p.name: p.read_bytes() for p in out.iterdir()}
    with monkeypatch.context() as patch:
        _break_figures(patch)
        assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 2
    assert {p.name: p.read_bytes() for p in out.iterdir()} == earlier
    assert [p.name for p in tmp_path.iterdir()] == ["out"]
    assert main(["burmester", PROBLEM, "--out", str(out), "--json"]) == 0
    assert _listed(out) == {p.name for p in out.iterdir()} == set(earlier)
    assert [p.name for p in tmp_path.iterdir()] == ["out"]


def test_an_out_that_is_a_link_is_written_through_it(tmp_path):
    """``--out LINK`` replaces the folder the link points at and leaves the link in place (it was replaced by a
    real folder, the earlier output left behind the link's old target)."""
    target, link = tmp_path / "target", tmp_path / "link"
    assert main(["burmester", PROBLEM, "--out", str(target), "--quiet"]) == 0
    (target / "report.md").write_text("earlier")
    link.symlink_to(target, target_is_directory=True)
    assert main(["burmester", PROBLEM, "--out", str(link), "--quiet"]) == 0
    assert link.is_symlink() and link.resolve() == target.resolve()
    assert (target / "report.md").read_text() != "earlier" and _listed(target) == {p.name for p in target.iterdir()}
    assert sorted(p.name for p in tmp_path.iterdir()) == ["link", "target"]


@pytest.mark.parametrize("plot", ["out/extra.png", "out/deeper/extra.png"])
def test_a_plot_inside_out_is_refused_before_the_work(tmp_path, monkeypatch, capsys, plot):
    """The --out folder is replaced whole, so a --plot file inside it would be lost: refused, naming both."""
    monkeypatch.setattr(burmester, "synthesize", lambda problem: pytest.fail("the work started"))
    (tmp_path / "out").mkdir()
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out"), "--plot", str(tmp_path / plot)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"--plot = {tmp_path / plot}: inside --out {tmp_path / 'out'}" in err


@pytest.mark.parametrize("content", ["a file", "a folder of other files"])
def test_an_out_that_is_not_ours_is_refused_before_the_work(tmp_path, monkeypatch, capsys, content):
    monkeypatch.setattr(burmester, "synthesize", lambda problem: pytest.fail("the work started"))
    out = tmp_path / "out"
    if content == "a file":
        out.write_text("keep me")
    else:
        out.mkdir()
        (out / "notes.txt").write_text("keep me")
    assert main(["burmester", PROBLEM, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith(f"transplanter: error: --out = {out}: ")
    assert "keep me" in (out.read_text() if content == "a file" else (out / "notes.txt").read_text())


class _Terminal(io.StringIO):
    def isatty(self):
        return True


@pytest.mark.parametrize("flag", ["--quiet", "--json"])
def test_quiet_and_json_keep_a_terminal_silent(tmp_path, monkeypatch, flag):
    monkeypatch.setattr(sys, "stderr", _Terminal())
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out"), flag]) == 0
    assert sys.stderr.getvalue() == ""


def test_progress_names_the_steps_on_a_terminal_and_stays_off_pipes(tmp_path, monkeypatch, capsys):
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out")]) == 0
    assert capsys.readouterr().err == ""                    # stderr is not a terminal here
    monkeypatch.setattr(sys, "stderr", _Terminal())
    assert main(["burmester", PROBLEM, "--out", str(tmp_path / "out")]) == 0
    lines = sys.stderr.getvalue().splitlines()
    assert lines[0] == "transplanter: synthesis ..." and lines[1].startswith("transplanter: synthesis done (")
    assert "transplanter: figures ..." in lines
    assert "transplanter:" not in capsys.readouterr().out


class _Failing:
    """A result that failed a check (the hook every command honours)."""
    passed = False
    failures = ("mesh overlap 0.3 mm", "undercut on the sun")

    def __init__(self, result):
        self._result = result

    def __getattr__(self, name):
        return getattr(self._result, name)


def test_a_result_that_fails_a_check_is_marked_and_exits_1(tmp_path, monkeypatch, capsys):
    real = burmester.synthesize
    monkeypatch.setattr(burmester, "synthesize", lambda problem: _Failing(real(problem)))
    out = tmp_path / "out"
    assert main(["burmester", PROBLEM, "--out", str(out), "--json"]) == 1
    captured = capsys.readouterr()
    assert captured.err == ("transplanter: failed: " + json.loads(captured.out)["source"]
                            + ": mesh overlap 0.3 mm; undercut on the sun\n")
    names = {p.name for p in out.iterdir()}
    assert names == {"FAILED-report.json", "FAILED-report.md", "FAILED-burmester.png"}
    report = json.loads((out / "FAILED-report.json").read_text())
    assert report["status"] == "FAILED" and report["failures"] == list(_Failing.failures)
    assert {n for names in report["files"].values() for n in names} == names
    assert (out / "FAILED-report.md").read_text().startswith("# FAILED: mesh overlap 0.3 mm")
    # a failed output may be replaced by the next run, as any earlier output
    monkeypatch.setattr(burmester, "synthesize", real)
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 0
    assert "report.json" in {p.name for p in out.iterdir()}


def test_library_progress_is_silent_unless_a_caller_shows_it(capsys):
    """``progress.report`` has the synthesis callback's signature (step, done, total)."""
    from transplanter import progress

    progress.report("refinement", 1, 17)
    shown = io.StringIO()
    with progress.showing(shown):
        progress.report("refinement", 2, 17)
        with progress.showing(shown, enabled=False):
            progress.report("refinement", 3, 17)
    assert shown.getvalue() == "transplanter: refinement 2/17\n"
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize("name, reason", [("a" * 300, "File name too long"), ("report.md/inside", "Not a directory")])
def test_an_out_the_system_cannot_take_is_named_as_out(tmp_path, capsys, name, reason):
    (tmp_path / "report.md").write_text("a file, not a folder\n")
    out = tmp_path / name
    assert main(["burmester", PROBLEM, "--out", str(out), "--quiet"]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"transplanter: error: --out = {out}: {reason}; expected a folder") and err.count("\n") == 1

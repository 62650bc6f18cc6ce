"""One runner for every command: the exit code, the FAILED marks, the files and the one stderr line follow the
result's passed, failures and produced, shown on results made to order."""
import json
import types
from dataclasses import dataclass

import pytest
from matplotlib.figure import Figure

from transplanter import cli
from transplanter.cli import Command, main
from transplanter.command_result import CommandResult


@dataclass(frozen=True)
class _Made(CommandResult):
    """A result made to order: its failures and whether its mechanism was produced."""

    failures: tuple[str, ...] = ()
    made: bool = True

    @property
    def source(self) -> str:
        return "made.toml"

    @property
    def produced(self) -> bool:
        return self.made

    def to_json(self):
        return {"source": self.source, "value": 1.5}

    def to_markdown(self, files=()):
        return "# Made to order\n\n" + "".join(f"![{name}]({name})\n" for name in files if name.endswith(".png"))

    def figure_drawers(self):
        return {"made": lambda: Figure(figsize=(1, 1))}

    def write_files(self, folder, animation=True, solids=True):
        (folder / "made.csv").write_text("a\n")
        return [folder / "made.csv"]


def _register(monkeypatch, result: CommandResult):
    package = types.ModuleType("made")
    package.load_problem = str
    monkeypatch.setattr(cli, "COMMANDS", (Command("made", "a result made to order", "any file", "made.csv", package,
                                                  run=lambda command, problem, args: result),))


@pytest.mark.parametrize("result, code", [(_Made(), 0), (_Made(("overlap 0.3 mm", "undercut")), 1),
                                          (_Made(("no train: the path turns back",), made=False), 2)])
def test_the_runner_sets_the_exit_code_from_the_result(result, code, tmp_path, monkeypatch, capsys):
    _register(monkeypatch, result)
    out = tmp_path / "out"
    assert main(["made", "problem.toml", "--out", str(out), "--json"]) == code
    captured = capsys.readouterr()
    report = json.loads(captured.out)
    prefix = "FAILED-" if code else ""
    names = {prefix + name for name in ("report.json", "report.md", "made.png", "made.csv")}
    assert {p.name for p in out.iterdir()} == names == {n for group in report["files"].values() for n in group}
    assert report == json.loads((out / f"{prefix}report.json").read_text())
    markdown = (out / f"{prefix}report.md").read_text()
    assert "![made.png](made.png)" in markdown
    if code:
        assert report["status"] == "FAILED" and report["failures"] == list(result.failures)
        assert markdown.startswith("# FAILED: " + "; ".join(result.failures))
        assert captured.err == "transplanter: failed: made.toml: " + "; ".join(result.failures) + "\n"
    else:
        assert "status" not in report and captured.err == ""


def test_the_screen_shows_the_text_and_the_files(tmp_path, monkeypatch, capsys):
    _register(monkeypatch, _Made(("overlap 0.3 mm",)))
    assert main(["made", "problem.toml", "--out", str(tmp_path / "out")]) == 1
    lines = capsys.readouterr().out.splitlines()
    assert lines[:2] == ["FAILED: overlap 0.3 mm", "Made to order"]
    assert lines[-1] == (f"wrote {tmp_path / 'out'}/: FAILED-made.csv, FAILED-made.png, FAILED-report.json, "
                         "FAILED-report.md")

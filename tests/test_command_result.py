"""One result protocol and one command runner: every registered command's result is a ``CommandResult``,
and the runner sets the exit code, the FAILED marks and the stderr line from passed, failures and produced."""
import argparse
import dataclasses
import json
import types
from dataclasses import dataclass
from pathlib import Path

import pytest
from matplotlib.figure import Figure

from transplanter import cli, parallelogram
from transplanter.cli import COMMANDS, Command, main
from transplanter.command_result import CommandResult
from transplanter.output_folder import report_json

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
#: A quick run of each command through the registry: its problem file and its own flags.
QUICK = {"burmester": ("burmester_4poses.toml", {}), "gear": ("gear_ellipse.toml", {}),
         "reverse": ("rice_hoe_reverse.toml", {}), "cam": ("cam_translating_design.toml", {}),
         "pickup": ("pickup_forward.toml", {}),
         "fivebar --design": ("vegetable_planting.toml", {"design": EXAMPLES / "vegetable_planting_table4.toml"}),
         "parallelogram --design": ("onion_transplanter.toml", {"design": EXAMPLES / "onion_published.toml"})}


def _registered(name: str) -> Command:
    return next(command for command in COMMANDS if command.name == name)


def _run(name: str, problem, **flags) -> CommandResult:
    command = _registered(name)
    return command.run(command, problem, argparse.Namespace(**{"design": None, "pick": None, **flags}))


def _check_protocol(result, folder: Path):
    """What the runner reads of a result, each in its promised form."""
    assert isinstance(result, CommandResult)
    assert isinstance(result.source, str) and result.source
    assert result.passed == (not result.failures) and all(isinstance(f, str) and f for f in result.failures)
    assert result.produced or not result.passed
    report = result.to_json()
    assert json.loads(report_json(report))["source"] == report["source"]
    assert result.to_markdown().startswith("# ") and not result.to_text().startswith("# ")
    figures = result.draw_figures()
    assert all(isinstance(stem, str) and isinstance(figure, Figure) for stem, figure in figures.items())
    written = result.write_files(folder, animation=False)
    assert all(path.parent == folder and path.is_file() for path in written)


@pytest.mark.parametrize("case", sorted(QUICK))
def test_a_registered_command_returns_a_command_result(case, tmp_path):
    name, design = case.split(" ")[0], QUICK[case][1]
    problem = _registered(name).package.load_problem(EXAMPLES / QUICK[case][0])
    _check_protocol(_run(name, problem, **design), tmp_path)


def test_the_five_bar_design_is_a_command_result(example_result, tmp_path):
    _check_protocol(example_result, tmp_path)


def test_the_onion_transplanter_design_is_a_command_result(tmp_path):
    small = dataclasses.replace(parallelogram.load_problem(EXAMPLES / "onion_transplanter.toml"), population=12,
                                generations=4, depth_band=(10.0, 40.0))
    _check_protocol(_run("parallelogram", small), tmp_path)


def test_every_command_is_checked_here():
    assert {case.split(" ")[0] for case in QUICK} | {"fivebar", "parallelogram"} == {c.name for c in COMMANDS}


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

    def draw_figures(self):
        return {"made": Figure(figsize=(1, 1))}

    def write_files(self, folder, animation=True):
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

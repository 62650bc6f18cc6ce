"""Checks every command with a tolerance analysis passes: ``--no-tolerance`` reaches its ``synthesize``, and a bad
``[tolerances]`` entry is one line and exit 2 before the work starts."""
from pathlib import Path

import pytest

from transplanter.cli import main
from transplanter.errors import InfeasibleError


def no_tolerance_reaches_synthesize(monkeypatch, package, command: str, example: Path):
    seen = {}

    def synthesize(problem, **options):
        seen.update(options)
        raise InfeasibleError("stopped here")

    monkeypatch.setattr(package, "synthesize", synthesize)
    assert main([command, str(example), "--quiet", "--no-tolerance"]) == 2
    assert seen["tolerance"] is False


def bad_tolerance_is_refused(tmp_path, capsys, monkeypatch, package, command: str, example: Path, entry: str,
                             fragment: str):
    path = tmp_path / "problem.toml"
    path.write_text(example.read_text() + f"\n[tolerances]\n{entry}\n")
    monkeypatch.setattr(package, "synthesize", lambda *a, **k: pytest.fail("the work started"))
    assert main([command, str(path), "--quiet"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], lines

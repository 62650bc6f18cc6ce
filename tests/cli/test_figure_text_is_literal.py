"""Titles, labels and file names are the user's text: drawn as written, never read as matplotlib mathtext
(an unbalanced ``$`` raised a parse error out of the figure-writing commands, with a traceback)."""
import dataclasses
import re
from pathlib import Path

import pytest

from transplanter import fivebar
from transplanter.cli import main
from transplanter.fivebar.animation import render_frames

ROOT = Path(__file__).resolve().parents[2]
UNBALANCED = r"a $\frac{$ b"


def _with_title(text: str, title: str) -> str:
    return f"title = '{title}'\n" + re.sub(r"^title = .*$", "", text, flags=re.M)


@pytest.mark.parametrize("command, example, edit, extra", [
    ("gear", "gear_ellipse.toml", lambda t: _with_title(t, UNBALANCED), ["--no-step"]),
    ("pickup", "pickup_forward.toml", lambda t: _with_title(t, UNBALANCED), ["--no-animation"]),
    ("burmester", "burmester_4poses.toml",
     lambda t: _with_title(t, UNBALANCED).replace('label = "P1"', f"label = '{UNBALANCED}'"), []),
])
def test_unbalanced_dollar_in_title_or_label_is_drawn(command, example, edit, extra, tmp_path, capsys):
    path = tmp_path / "problem.toml"
    path.write_text(edit((ROOT / "examples" / example).read_text()))
    assert UNBALANCED in path.read_text()
    assert main([command, str(path), "--out", str(tmp_path / "out"), "--quiet", *extra]) == 0
    assert capsys.readouterr().err == ""
    assert any(p.suffix == ".png" for p in (tmp_path / "out").iterdir())


def test_fivebar_figures_and_animation_draw_labels_literally(example_result):
    problem = dataclasses.replace(example_result.problem, labels=(UNBALANCED,) + example_result.problem.labels[1:])
    result = dataclasses.replace(example_result, problem=problem)
    for figure in fivebar.draw_figures(result).values():
        figure.draw_without_rendering()
    assert len(render_frames(result, frames=1)) == 1

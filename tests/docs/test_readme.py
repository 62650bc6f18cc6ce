"""The README's Python API examples run as written, and its test command is the one CI runs."""
from __future__ import annotations

import re
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402  (after choosing the backend)

ROOT = Path(__file__).resolve().parents[2]
README = (ROOT / "README.md").read_text()


def section(text: str, title: str) -> str:
    """The body of the level-2 section ``title``, up to the next level-2 heading."""
    match = re.search(rf"^## {re.escape(title)}\n(.*?)(?=^## |\Z)", text, re.MULTILINE | re.DOTALL)
    assert match, f"README has no section '## {title}'"
    return match.group(1)


def python_blocks(text: str) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", text, re.MULTILINE | re.DOTALL)


API_BLOCKS = python_blocks(section(README, "Python API"))


def test_every_job_has_an_example():
    imported = {job for block in API_BLOCKS
                for job in re.findall(r"^from transplanter import (\w+)", block, re.MULTILINE)}
    assert imported == {"fivebar", "burmester", "gears", "reverse"}


@pytest.fixture
def synthesis_once(request):
    """A block that calls ``fivebar.synthesize`` gets the test process's one synthesis of the bundled example
    (``example_result_from_synthesize``), one that calls ``reverse.synthesize`` its one synthesis of the rice hoe
    (``rice_result_from_synthesize``, shared with test_python_api.py); the other blocks run without them."""
    block = request.node.callspec.params["block"]
    if "fivebar.synthesize(" in block:
        request.getfixturevalue("example_result_from_synthesize")
    if "reverse.synthesize(" in block:
        request.getfixturevalue("rice_result_from_synthesize")


@pytest.mark.parametrize("block", API_BLOCKS, ids=[f"block{k}" for k in range(len(API_BLOCKS))])
def test_api_example_runs(block, tmp_path, monkeypatch, synthesis_once):
    """Run in an empty folder that sees the repository's examples/, so outputs land in tmp."""
    (tmp_path / "examples").symlink_to(ROOT / "examples", target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    try:
        exec(compile(block, "README.md (Python API)", "exec"), {"__name__": "readme_example"})
    finally:
        plt.close("all")


def test_test_command_is_the_ci_command():
    ci_command = (ROOT / ".ci" / "run").read_text().strip().splitlines()[-1]
    assert f"\n{ci_command}\n" in section(README, "The two commands")

"""design.toml of a cam run read back with ``--design``: the same cam, checks and drawings' numbers."""
from pathlib import Path

import pytest

from tests.cli.design_round_trip import assert_round_trip, read_report
from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
#: What only a design-mode run reports (it searched; the design read back is evaluated once).
SEARCH_ONLY = {"designed_base_radius", "cams_evaluated", "timings_s", "files"}


@pytest.mark.parametrize("example", ["cam_translating_design.toml", "cam_flat_faced.toml"])
def test_design_file_is_written_listed_and_read_back(tmp_path, example):
    run, given = tmp_path / "run", tmp_path / "given"
    assert main(["cam", str(ROOT / "examples" / example), "--quiet", "--no-step", "--out", str(run)]) == 0
    report = read_report(run)
    assert report["files"]["design"] == ["design.toml"]
    assert main(["cam", str(ROOT / "examples" / example), "--design", str(run / "design.toml"), "--quiet", "--no-step",
                 "--out", str(given)]) == 0
    again = read_report(given)
    assert set(report) == set(again)
    assert_round_trip(report, again, tuple(sorted(set(report) - SEARCH_ONLY)))
    assert again["designed_base_radius"] is False and again["cams_evaluated"] == 1


def test_the_design_sets_the_base_circle(tmp_path, capsys):
    """The smallest base circle of the translating example, 2 mm smaller, breaks the pressure-angle limit."""
    run = tmp_path / "run"
    example = str(ROOT / "examples/cam_translating_design.toml")
    assert main(["cam", example, "--quiet", "--no-step", "--out", str(run)]) == 0
    smallest = read_report(run)["base_radius_mm"]
    path = tmp_path / "smaller.toml"
    path.write_text(f"[cam]\nbase_radius_mm = {smallest - 2.0!r}\n")
    assert main(["cam", example, "--design", str(path), "--json"]) == 1
    assert "pressure" in capsys.readouterr().err

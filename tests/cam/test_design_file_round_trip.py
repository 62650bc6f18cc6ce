"""design.toml of a cam run read back with ``--design``: the same cam, checks and drawings' numbers."""
from pathlib import Path

import pytest

from tests.cli.design_round_trip import assert_round_trip, read_report
from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
#: What only a design-mode run reports (it searched; the design read back is evaluated once).
SEARCH_ONLY = {"designed_base_radius", "cams_evaluated", "timings_s", "files"}


@pytest.fixture(scope="module")
def run_of(tmp_path_factory):
    """The folder of ``cam <example> --quiet --no-step --out``, each example run once for the tests that read it."""
    folders = {}

    def run(example: str) -> Path:
        if example not in folders:
            folders[example] = tmp_path_factory.mktemp(Path(example).stem) / "run"
            assert main(["cam", str(ROOT / "examples" / example), "--quiet", "--no-step",
                         "--out", str(folders[example])]) == 0
        return folders[example]
    return run


@pytest.mark.parametrize("example", ["cam_translating_design.toml", "cam_flat_faced.toml"])
def test_design_file_is_written_listed_and_read_back(tmp_path, example, run_of):
    run, given = run_of(example), tmp_path / "given"
    report = read_report(run)
    assert report["files"]["design"] == ["design.toml"]
    assert main(["cam", str(ROOT / "examples" / example), "--design", str(run / "design.toml"), "--quiet", "--no-step",
                 "--out", str(given)]) == 0
    again = read_report(given)
    assert set(report) == set(again)
    assert_round_trip(report, again, tuple(sorted(set(report) - SEARCH_ONLY)))
    assert again["designed_base_radius"] is False and again["cams_evaluated"] == 1


def test_the_design_sets_the_base_circle(tmp_path, capsys, run_of):
    """The smallest base circle of the translating example, 2 mm smaller, breaks the pressure-angle limit."""
    example = str(ROOT / "examples/cam_translating_design.toml")
    smallest = read_report(run_of("cam_translating_design.toml"))["base_radius_mm"]
    path = tmp_path / "smaller.toml"
    path.write_text(f"[cam]\nbase_radius_mm = {smallest - 2.0!r}\n")
    assert main(["cam", example, "--design", str(path), "--json"]) == 1
    assert "pressure" in capsys.readouterr().err

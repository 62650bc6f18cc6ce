"""design.toml of an onion-transplanter run read back with ``--design``: the same design and trajectory; the
depth band of a given design met within a tolerance relative to the band."""
import dataclasses
import tomllib
from pathlib import Path

import pytest

from tests.cli.design_round_trip import assert_round_trip, read_report
from transplanter.cli import main
from transplanter.parallelogram import evaluate_design, load_design, load_problem
from transplanter.parallelogram.synthesis import AGREEMENT, requirement_failures

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "examples/onion_transplanter.toml"


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """A small search through the command, with --out."""
    folder = tmp_path_factory.mktemp("run")
    path = folder / "small.toml"
    path.write_text(PROBLEM.read_text().replace("population = 100", "population = 16")
                    .replace("generations = 100", "generations = 6"))
    out = folder / "out"
    assert main(["parallelogram", str(path), "--no-animation", "--no-step", "--quiet", "--no-tolerance", "--out",
                 str(out)]) == 0
    return path, out


def test_design_file_is_written_listed_and_read_back(run, tmp_path):
    path, out = run
    report = read_report(out)
    assert report["files"]["design"] == ["design.toml"]
    assert set(tomllib.loads((out / "design.toml").read_text())["design"]) == set(report["design"])
    given = tmp_path / "given"
    assert main(["parallelogram", str(path), "--design", str(out / "design.toml"), "--quiet", "--no-tolerance",
                 "--no-step", "--out", str(given)]) == 0
    assert_round_trip(report, read_report(given), ("design", "trajectory"))


def test_a_design_on_the_end_of_its_depth_band_meets_it():
    """The published design's closed curve moved to plant exactly at the band's low end, and by the last bits
    below it, meets the band; moved below it by more than the tolerance, it does not."""
    problem = load_problem(PROBLEM)
    report = evaluate_design(problem, load_design(ROOT / "examples/onion_published.toml"), tolerance=False)
    low, high = problem.depth_band
    for depth, fails in ((low, False), (low * (1 - 1e-14), False), (low - 2 * AGREEMENT * high, True)):
        moved = dataclasses.replace(report.closed, depth=depth)
        failures = [f for f in requirement_failures(problem, moved, report.gear) if f.startswith("depth")]
        assert bool(failures) == fails, (depth, failures)

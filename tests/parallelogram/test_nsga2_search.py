"""The onion transplanter of the onion-transplanter paper: objectives and constraints, NSGA-II (small runs), the
design command."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from transplanter.cli import main
from transplanter.errors import InfeasibleError
from transplanter.gears.pair import design_pair
from transplanter.gears.pitch_curves import denatured_limacon
from transplanter.parallelogram import load_problem
from transplanter.parallelogram.objectives import CONSTRAINTS, score
from transplanter.parallelogram.search import knee_order, nsga2

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "examples/onion_transplanter.toml"


@pytest.fixture(scope="module")
def problem():
    return dataclasses.replace(load_problem(PROBLEM), population=12, generations=4)


def test_whole_population_equals_one_design_at_a_time(problem, rng):
    """The vectorised score of a population is the per-individual loop's, design by design."""
    count = 12
    variables = {"m11": rng.uniform(1, 2, count), "b": rng.uniform(5, 20, count), "l": rng.uniform(40, 70, count),
                 "l1": rng.uniform(60, 100, count), "alpha": np.radians(rng.uniform(-10, 20, count))}
    whole = score(problem, variables, 512)
    for k in range(count):
        one = score(problem, {n: v[k:k + 1] for n, v in variables.items()}, 512)
        assert np.allclose(one.objectives[0], whole.objectives[k], rtol=1e-12, atol=1e-12)
        assert np.allclose(one.constraints[0], whole.constraints[k], rtol=1e-12, atol=1e-12)


def test_gear_constraints_agree_with_the_gear_library(problem):
    """A driver k = b/l = 0.5 with m11 = 2.5 is concave (the gear library's sampled curve says so) and
    violates the convexity constraint; the published gear meets every gear constraint."""
    variables = {"m11": np.array([2.5, 1.5]), "b": np.array([26.5, 13.0]), "l": np.array([53.0, 53.0])}
    g = score(problem, variables, 512).constraints
    column = {name: k for k, name in enumerate(CONSTRAINTS)}
    concave = design_pair(denatured_limacon(53.0, 26.5, 2.5, 1 / (2 - 1 / 2.5)), 1)
    assert (concave.convexity[0] <= 0).any()
    assert g[0, column["driver_convex"]] > 0
    for name in ("driver_convex", "driven_convex", "driver_undercut_free", "driven_undercut_free"):
        assert g[1, column[name]] < 0


def test_knee_of_a_constructed_front():
    """Normalised by the front's range, the point nearest the ideal point is the knee."""
    front = np.array([[0.0, 10.0, 1.0], [4.0, 4.0, 0.4], [10.0, 0.0, 0.0], [1.0, 9.5, 0.9]])
    assert knee_order(front)[0] == 1


def test_search_is_seeded_and_reproducible(problem):
    """Same seed, same Pareto set; the reported values are those of the designs returned."""
    problem = dataclasses.replace(problem, depth_band=(10.0, 40.0))
    first, second = nsga2(problem), nsga2(problem)
    assert np.array_equal(first.designs, second.designs)
    assert np.array_equal(first.objectives, second.objectives)
    again = score(problem, dict(zip(first.names, first.designs.T, strict=True)), 512)
    assert np.allclose(again.objectives, first.objectives, rtol=1e-12, atol=1e-12)
    assert np.all(again.constraints <= 0)


def test_unreachable_depth_band_says_so_with_the_closest_design(problem):
    bad = dataclasses.replace(problem, depth_band=(200.0, 210.0), depth_target=205.0)
    with pytest.raises(InfeasibleError, match=r"objectives.depth_band_mm = \[200.0, 210.0\].*closest design"):
        nsga2(bad)


def test_design_command_json_and_files(tmp_path):
    """A small search through the command: pareto, knee, gear, trajectory, timings; pareto.csv has every design."""
    text = PROBLEM.read_text().replace("population = 100", "population = 16").replace("generations = 100",
                                                                                        "generations = 6")
    path = tmp_path / "small.toml"
    path.write_text(text)
    out = tmp_path / "out"
    assert main(["parallelogram", str(path), "--json", "--no-animation", "--no-tolerance", "--no-step", "--out",
                 str(out)]) in (0, 1)
    report = json.loads((out / "report.json").read_text()) if (out / "report.json").exists() else \
        json.loads((out / "FAILED-report.json").read_text())
    assert {"pareto", "knee", "gear", "trajectory", "timings_s", "polished"} <= set(report)
    assert report["knee"] == report["pareto"][0]
    assert len(report["published"]["evaluations"]) == 4 and report["published"]["paper"]["depth_mm"] == 27.0
    lines = (out / "pareto.csv").read_text().strip().splitlines()
    assert len(lines) == len(report["pareto"]) + 1
    assert report["gear"]["center_distance"] > 0
    written = {p.name for p in out.iterdir()}
    assert {"trajectory.csv", "driver.dxf", "driven.svg", "pareto.png"} <= {n.removeprefix("FAILED-") for n in written}


def test_animation_frames(problem, tmp_path):
    """A few frames of one cycle, written as a GIF."""
    from PIL import Image

    from transplanter.parallelogram import synthesize
    from transplanter.parallelogram.animation import write_animation

    result = synthesize(dataclasses.replace(problem, depth_band=(10.0, 40.0)), tolerance=False)
    gif = write_animation(result, tmp_path, frames=3)
    with Image.open(gif) as image:
        assert image.n_frames == 3


def test_polish_dominates_the_knee_and_is_checked_independently():
    """From a Pareto-like start near the published optimum, the NLP reaches Vx(t_E) = 0 and H = 25 mm, which the
    independent fine-grid evaluation confirms, with f3 no worse: the polished design dominates its start."""
    from transplanter.parallelogram.evaluation import evaluate
    from transplanter.parallelogram.result import objective_values
    from transplanter.parallelogram.synthesis import _polish

    problem = load_problem(PROBLEM)
    start = {**problem.design, "m11": 1.47, "b": 12.8666, "l": 54.4989, "l1": 80.0088, "alpha": np.radians(7.7856)}
    before = evaluate(problem, start)
    polished = _polish(problem, start, before)
    assert polished.status == "Solve_Succeeded"
    assert polished.failures(problem) == ()
    after = objective_values(problem, polished.evaluation)
    assert abs(polished.evaluation.vx_release) < 1e-9 * problem.forward_speed
    assert abs(polished.evaluation.depth - problem.depth_target) < 1e-9 * problem.depth_target
    assert np.all(after <= objective_values(problem, before))
    assert polished.dominates_start

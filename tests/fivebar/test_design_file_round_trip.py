"""design.toml of a five-bar run read back with ``--design``: the same design table, key-pose errors and whole
turn; the report's names in design files; the ranges of a given design met within a tolerance relative to
the problem."""
import json
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest
from matplotlib.figure import Figure

from tests.cli.design_round_trip import assert_round_trip, read_report
from transplanter import fivebar
from transplanter.cli import main
from transplanter.errors import ProblemError
from transplanter.fivebar.candidate import range_values
from transplanter.fivebar.evaluation import RANGE_TOLERANCE, evaluate_design, load_design
from transplanter.fivebar.nlp import reach
from transplanter.fivebar.problem import load_problem
from transplanter.fivebar.report import design_json

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/vegetable_planting.toml"
TABLE4 = ROOT / "examples/vegetable_planting_table4.toml"
#: What a run and its design read back both report of the design.
ROUND_TRIP_KEYS = ("design", "key_pose_position_errors_mm", "key_pose_angle_errors_deg", "min_closure_margin",
                   "ratio_range", "relative_angle_monotonic")


@pytest.fixture(scope="module")
def run(example_result, tmp_path_factory, monkeypatch_module):
    """The main job's run with --out (the synthesis is the session's; one small figure, no animation)."""
    monkeypatch_module.setattr(fivebar, "synthesize", lambda problem, **options: example_result)
    monkeypatch_module.setattr(fivebar.FiveBarResult, "figure_drawers",
                               lambda result: {"plain": lambda: Figure((1, 1))})
    out = tmp_path_factory.mktemp("run") / "out"
    assert main(["fivebar", str(EXAMPLE), "--out", str(out), "--no-animation", "--no-step", "--quiet"]) == 0
    return out


@pytest.fixture(scope="module")
def monkeypatch_module():
    with pytest.MonkeyPatch.context() as patch:
        yield patch


def test_design_file_is_written_and_listed(run):
    assert read_report(run)["files"]["design"] == ["design.toml"]
    design = tomllib.loads((run / "design.toml").read_text())
    assert set(design) == {"title", "description", "design", "relative_angle"}
    names = set(read_report(run)["design"])
    assert set(design["design"]) <= names      # the report's names


def test_design_read_back_reproduces_the_report(run, tmp_path):
    out = tmp_path / "given"
    assert main(["fivebar", str(EXAMPLE), "--design", str(run / "design.toml"), "--out", str(out), "--quiet"]) == 0
    assert_round_trip(read_report(run), read_report(out), ROUND_TRIP_KEYS)


def test_a_design_moved_off_its_motion_misses_the_key_poses(run, tmp_path):
    """The check can fail: the carrier 0.01 mm longer misses the key poses by about that much."""
    text = (run / "design.toml").read_text()
    length = tomllib.loads(text)["design"]["carrier_length_OA"]
    moved = tmp_path / "moved.toml"
    moved.write_text(text.replace(f"carrier_length_OA = {length!r}", f"carrier_length_OA = {length + 0.01!r}"))
    evaluation = evaluate_design(load_problem(EXAMPLE), load_design(moved))
    assert 1e-3 < evaluation.position_errors_mm.max() < 0.03


def test_older_names_are_read_with_a_note(tmp_path):
    text = TABLE4.read_text()
    old = tmp_path / "old.toml"
    old.write_text(re.sub(r"^carrier_length_OA =", "carrier_length =", text, flags=re.M))
    with pytest.warns(UserWarning, match=r"design\.carrier_length is now named carrier_length_OA"):
        given = load_design(old)
    assert given.carrier_length_OA == load_design(TABLE4).carrier_length_OA == 47.47
    both = tmp_path / "both.toml"
    both.write_text(text.replace("carrier_length_OA = 47.47", "carrier_length_OA = 47.47\ncarrier_length = 47.47"))
    with pytest.raises(ProblemError, match=r"design\.carrier_length = 47\.47: expected only carrier_length_OA"):
        load_design(both)


def test_a_design_rounded_onto_a_range_end_meets_the_range(example_result, tmp_path):
    """The main job's design with EP rounded to the end of its range: EP computes 1e-14 beyond it, within the
    relative tolerance; a design 1e-6 of the reach beyond it still fails."""
    problem, mech = example_result.problem, example_result.design.mech
    low, high = problem.ranges["ep"]
    table = design_json(mech, problem.poses[0])
    for ep, fails in ((high, False), (high * (1 + 1e-14), False), (high + 1e-6 * reach(problem), True)):
        path = tmp_path / "rounded.toml"
        rows = [f"{key} = {json.dumps(table[key])}" for key in ("carrier_length_OA", "carrier_angle_deg",
                                                              "rod_length_AF", "rod_angle_deg",
                                                              "receiving_plate_length_BE", "hinge_B", "hinge_E")]
        path.write_text("[design]\n" + "\n".join(rows) + f"\npush_plate_EP = {ep!r}\n")
        evaluation = evaluate_design(problem, load_design(path))
        assert np.isclose(range_values(problem, evaluation.mech)["ep"], ep, rtol=1e-12, atol=0)
        defects = [d for d in evaluation.candidate.defects if d.startswith("ranges.ep")]
        assert bool(defects) == fails, (ep, defects)
    assert RANGE_TOLERANCE * reach(problem) < 1e-6 * reach(problem)


def _with_key_poses(path: Path, chosen: np.ndarray) -> Path:
    """The published design with [key_poses] (rows x, y, direction, turn; mm, rad)."""
    columns = (chosen[:, 0], chosen[:, 1], np.degrees(chosen[:, 2]), np.degrees(chosen[:, 3]))
    rows = [f"{name} = {[float(v) for v in column]}"
            for name, column in zip(("x", "y", "angle_deg", "carrier_turn_deg"), columns, strict=True)]
    path.write_text(TABLE4.read_text() + "\n[key_poses]\n" + "\n".join(rows) + "\n")
    return path


def test_chosen_key_poses_are_judged_at_and_against_the_bands(tmp_path):
    """Key poses inside a banded problem's bands are the ones the design is judged at; one beyond its band by
    1 mm is named; a problem without bands takes its own poses only."""
    banded = load_problem(ROOT / "examples/vegetable_planting_bands.toml")
    low, high = banded.pose_bands.low, banded.pose_bands.high
    inside = low + 0.3 * (high - low)
    evaluation = evaluate_design(banded, load_design(_with_key_poses(tmp_path / "inside.toml", inside)))
    assert np.abs(evaluation.problem.poses - inside[:, :3]).max() < 1e-12
    assert not [d for d in evaluation.candidate.defects if d.startswith("key_poses")]
    beyond = inside.copy()
    beyond[1, 0] = high[1, 0] + 1.0
    evaluation = evaluate_design(banded, load_design(_with_key_poses(tmp_path / "beyond.toml", beyond)))
    assert [d for d in evaluation.candidate.defects if d.startswith("key_poses")] == [
        f"key_poses.{banded.labels[1]}.x: the design's key pose is outside the problem's band"]
    exact = load_problem(EXAMPLE)
    own = np.c_[exact.poses, exact.carrier_turns]
    for poses, named in ((own, False), (inside, True)):
        evaluation = evaluate_design(exact, load_design(_with_key_poses(tmp_path / "exact.toml", poses)))
        assert bool([d for d in evaluation.candidate.defects if d.startswith("key_poses")]) == named

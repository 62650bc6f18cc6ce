"""design.toml of a reverse run read back with ``--design``: the same arm, motion, train and round trip."""
from pathlib import Path

from tests.cli.design_round_trip import assert_round_trip, read_report
from transplanter.cli import main
from transplanter.reverse import evaluate_design, load_design, load_problem

ROOT = Path(__file__).resolve().parents[2]
RICE = ROOT / "examples/rice_hoe_reverse.toml"
#: What a run and its design read back both report (all but where the lengths came from).
ROUND_TRIP_KEYS = ("trajectory", "carrier_length", "arm_length", "direction", "touches", "branch_segments",
                   "monotonic", "ratio_range", "gears", "gear_closure_errors", "roundtrip_max_error_mm",
                   "contact_gap_max_mm", "center_distances", "correction_factor_k", "stage_one_exponent")


def test_design_file_is_written_listed_and_read_back(tmp_path, rice_result_from_synthesize):
    """Both runs without the tolerance analysis: no key compared reads it. The first run's train is the session's
    ``rice_result``; the second, made from design.toml, is synthesised here."""
    run, given = tmp_path / "run", tmp_path / "given"
    assert main(["reverse", str(RICE), "--quiet", "--no-step", "--no-tolerance", "--out", str(run)]) == 0
    assert read_report(run)["files"]["design"] == ["design.toml"]
    assert main(["reverse", str(RICE), "--design", str(run / "design.toml"), "--quiet", "--no-step", "--no-tolerance",
                 "--out", str(given)]) == 0
    assert_round_trip(read_report(run), read_report(given), ROUND_TRIP_KEYS)
    assert read_report(given)["lengths_from"] == "problem file"


def test_the_design_sets_the_arm_and_the_train(tmp_path):
    """A design with the pivot moved 1 mm and the carrier 1 mm longer is made with those, not the file's."""
    path = tmp_path / "design.toml"
    path.write_text('[arm]\npivot = [1.0, 0.0]\ncarrier_length = 93.3\narm_length = 162.0\ndirection = "clockwise"\n'
                    '[train]\nmodule = 2.0\ncenter_distances = [46.0, 47.3]\n')
    result = evaluate_design(load_problem(RICE), load_design(path))
    assert (result.motion.carrier_length, result.motion.arm_length) == (93.3, 162.0)
    assert result.problem.pivot.tolist() == [1.0, 0.0] and result.problem.center_distances == (46.0, 47.3)
    assert abs(result.problem.points - (load_problem(RICE).points - [1.0, 0.0])).max() < 1e-12     # the same path


def test_a_design_without_its_lengths_is_one_line(tmp_path, capsys):
    path = tmp_path / "design.toml"
    path.write_text('[arm]\ndirection = "clockwise"\n')
    assert main(["reverse", str(RICE), "--design", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "arm.carrier_length = None: expected the carrier and arm lengths" in err

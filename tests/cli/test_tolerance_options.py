"""The design commands that analyse their built mechanism's tolerances: ``--no-tolerance`` reaches the
synthesis, and a bad ``[tolerances]`` entry is one line naming the field, exit 2, before the work."""
from pathlib import Path

import pytest

from transplanter import fivebar, parallelogram, reverse
from transplanter.cli import main
from transplanter.errors import InfeasibleError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: command, its package, its example, and bad [tolerances] entries with what the message must name.
COMMANDS = [
    ("fivebar", fivebar, "vegetable_planting.toml",
     [("rod_length_AF = -0.1", "tolerances.rod_length_AF = -0.1"),
      ("rod_length = 0.1", "tolerances.rod_length = 0.1"),
      ("pose_position_mm = 0.0", "tolerances.pose_position_mm = 0.0"),
      ("phase_sun = nan", "tolerances.phase_sun = nan")]),
    ("parallelogram", parallelogram, "onion_transplanter.toml",
     [("l1 = -0.1", "tolerances.l1 = -0.1"), ("crank = 0.1", "tolerances.crank = 0.1"),
      ("pose_angle_deg = 0.0", "tolerances.pose_angle_deg = 0.0"), ("backlash = inf", "tolerances.backlash = inf")]),
    ("reverse", reverse, "rice_hoe_reverse.toml",
     [("arm_length = -0.1", "tolerances.arm_length = -0.1"),
      ("carrier_length = 0.1", "tolerances.carrier_length = 0.1"),
      ("pose_angle_deg = 0.0", "tolerances.pose_angle_deg = 0.0"), ("phase_sun = inf", "tolerances.phase_sun = inf"),
      ("path_accuracy_mm = 0.0", "tolerances.path_accuracy_mm = 0.0")]),
]


@pytest.mark.parametrize("command, package, example", [c[:3] for c in COMMANDS])
def test_no_tolerance_flag_skips_the_analysis(monkeypatch, command, package, example):
    seen = {}

    def synthesize(problem, **options):
        seen.update(options)
        raise InfeasibleError("stopped here")

    monkeypatch.setattr(package, "synthesize", synthesize)
    assert main([command, str(EXAMPLES / example), "--quiet", "--no-tolerance"]) == 2
    assert seen["tolerance"] is False


@pytest.mark.parametrize("command, package, example, entry, fragment",
                         [(*c[:3], *bad) for c in COMMANDS for bad in c[3]])
def test_bad_tolerances_give_one_line_and_exit_2_before_the_work(tmp_path, capsys, monkeypatch, command, package,
                                                                 example, entry, fragment):
    path = tmp_path / "problem.toml"
    path.write_text((EXAMPLES / example).read_text() + f"\n[tolerances]\n{entry}\n")
    monkeypatch.setattr(package, "synthesize", lambda *a, **k: pytest.fail("the work started"))
    assert main([command, str(path), "--quiet"]) == 2
    lines = capsys.readouterr().err.strip().splitlines()
    assert len(lines) == 1 and fragment in lines[0], lines

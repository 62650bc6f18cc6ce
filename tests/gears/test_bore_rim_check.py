"""A cut gear pair whose keyed bores come too close to the teeth fails the gear command: exit 1, every file marked
FAILED-, the numbers in the report; the same check in the onion transplanter's requirements."""
import json
import subprocess
import sys
import tomllib
from pathlib import Path

import numpy as np

from transplanter import gears, parallelogram
from transplanter.parallelogram.synthesis import requirement_failures
from transplanter.shafts.keys import STANDARD_DIAMETERS, parallel_key
from transplanter.shafts.sizing import min_rim

ROOT = Path(__file__).resolve().parents[2]
#: 12 teeth of module 2 on a nearly round ellipse (30 deg pressure angle against undercut): a root radius under
#: 9 mm, so the smallest standard bore's keyway leaves less than 1.2 tooth heights under the teeth
SMALL_PAIR = ((ROOT / "examples/gear_ellipse.toml").read_text().replace("teeth = 30", "teeth = 12")
              .replace("eccentricity = 0.3", "eccentricity = 0.05")
              .replace("pressure_angle_deg = 20.0", "pressure_angle_deg = 30.0"))


def _small_pair_failures(root: float) -> str:
    """The failure the rim check must give for a gear of root radius ``root`` on the smallest standard bore."""
    diameter = STANDARD_DIAMETERS[0]
    reach = diameter / 2 + parallel_key(diameter).hub_depth
    return (f"a {diameter:g} mm bore's keyway reaches {reach:.3f} mm from the centre, leaving {root - reach:.3f} mm "
            f"to the root at {root:.3f} mm; at least {min_rim(2.0):.3f} mm expected")


def test_a_bore_near_the_teeth_fails_the_gear_command_with_the_numbers(tmp_path):
    problem, out = tmp_path / "small.toml", tmp_path / "out"
    problem.write_text(SMALL_PAIR)
    run = subprocess.run([sys.executable, "-m", "transplanter", "gear", str(problem), "--no-step", "--out", str(out)],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 1 and run.stderr.count("\n") == 1 and "driver bore" in run.stderr
    assert all(path.name.startswith("FAILED-") for path in out.iterdir())
    report = json.loads((out / "FAILED-report.json").read_text())
    for name in ("driver", "driven"):
        outline = np.loadtxt(out / f"FAILED-{name}_teeth.csv", delimiter=",", skiprows=1)
        expected = f"{name} bore: " + _small_pair_failures(float(np.linalg.norm(outline, axis=1).min()))
        assert any(failure.startswith(expected) for failure in report["failures"]), report["failures"]


def test_the_onion_transplanters_requirements_hold_its_gears_bores_to_the_same_check():
    pair = gears.synthesize(gears.parse_problem(tomllib.loads(SMALL_PAIR), "small"))
    problem = parallelogram.load_problem(ROOT / "examples/onion_transplanter.toml")
    report = parallelogram.evaluate_design(problem, parallelogram.load_design(ROOT / "examples/onion_published.toml"))
    published = requirement_failures(problem, report.closed, report.gear)
    failures = requirement_failures(problem, report.closed, pair)
    assert [failure.split(":")[0] for failure in failures if failure not in published] == ["driver bore",
                                                                                            "driven bore"]
    assert not any("bore" in failure for failure in published)

"""The gear command: JSON fields, drawings that CAD can read, bad input."""
import contextlib
import io
import json
import subprocess
import sys
import warnings
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import ezdxf
import numpy as np
import pytest
from scipy.special import ellipe

from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = sorted((ROOT / "examples").glob("gear_*.toml"))


def _command(*args):
    return [sys.executable, "-m", "transplanter", "gear", *map(str, args)]


def _run(*args):
    return subprocess.run(_command(*args), capture_output=True, text=True, cwd=ROOT)


def test_one_example_per_family(capsys):
    """Every example runs to the end (the only full run of most), by the command in this process (the interpreter's
    entry to it is run in the tests below): a Python start and the package's imports per example would cost more
    CPU than most examples' runs."""
    families = set()
    for path in EXAMPLES:
        code = main(["gear", str(path), "--json"])
        stdout, stderr = capsys.readouterr()
        assert code == 0, (path.name, stderr)
        families.add(json.loads(stdout)["driver"]["family"])
    assert families == {"ellipse", "higher_order_ellipse", "denatured_ellipse", "limacon", "denatured_limacon",
                        "spline", "ratio", "composite"}


def test_json_fields_and_drawings(tmp_path):
    run = _run(ROOT / "examples/gear_ellipse.toml", "--json", "--no-step", "--out", tmp_path)
    assert run.returncode == 0, run.stderr
    report = json.loads(run.stdout)
    for key in ("center_distance", "orders", "ratio_range", "perimeters", "convex", "min_curvature_radius",
                "tooth_counts", "module", "undercut", "closure_error"):
        assert key in report
    assert report["orders"] == [1, 1] and report["tooth_counts"]["nearest"] == [30, 30]
    assert abs(report["closure_error"]) < 1e-10
    outline = np.loadtxt(tmp_path / "driver_teeth.csv", delimiter=",", skiprows=1)
    polyline = next(iter(ezdxf.readfile(tmp_path / "driver.dxf").modelspace().query('LWPOLYLINE[layer=="OUTLINE"]')))
    assert polyline.closed and len(polyline) == len(outline)
    assert np.allclose(np.array(polyline.get_points("xy")), outline, atol=1e-6)
    pitch = np.loadtxt(tmp_path / "pitch_curves.csv", delimiter=",", skiprows=1)
    drawing = ezdxf.readfile(tmp_path / "driver.dxf")
    assert drawing.header["$INSUNITS"] == 4     # millimetres
    on_pitch = list(drawing.modelspace().query('LWPOLYLINE[layer=="PITCH"]'))
    assert len(on_pitch) == 1                   # the pitch curve, on its own layer, as in pitch_curves.csv
    assert np.allclose(np.array(on_pitch[0].get_points("xy")), pitch[:, 4:6], atol=1e-6)
    svg = ElementTree.parse(tmp_path / "driven.svg").getroot()
    assert svg.get("width").endswith("mm")
    assert pitch.shape[1] == 13
    for name in ("gear_mesh.png", "gear_kinematics.png", "gear_curvature.png"):
        assert (tmp_path / name).read_bytes()[:4] == b"\x89PNG"
    # focal ellipses scaled to a perimeter of pi m Z = 60 pi: 4 A E(e^2) = 60 pi, center distance 2 A
    assert report["center_distance"] == pytest.approx(30 * np.pi / ellipe(0.3**2), rel=1e-12)
    markdown = (tmp_path / "report.md").read_text()
    # regression pin of the report's wording; the number is checked against the closed form just above
    assert "center distance 61.40586" in markdown and "![gear_mesh.png](gear_mesh.png)" in markdown


BAD = {
    "unknown family": ('[driver]\nfamily = "cycloid"\n', ["driver.family", "cycloid", "one of"]),
    "radius reaches zero": ('[driver]\nfamily = "limacon"\nbase = 10.0\namplitude = 12.0\n',
                            ["driver.amplitude = 12.0", "below driver.base = 10 mm"]),
    "ratio touches zero": ('[driver]\nfamily = "ratio"\nphi_deg = [0, 90, 180, 270]\nratio = [1.0, 0.0, 1.0, 2.0]\n'
                           '[pair]\ncenter_distance = 50.0\n', ["driver.ratio", "0.0", "reverses the driven gear"]),
    "ratio cannot close": ('[driver]\nfamily = "ratio"\nphi_deg = [0, 90, 180, 270]\nratio = [1.0, 1.5, 1.0, 2.0]\n'
                           '[pair]\ncenter_distance = 50.0\n', ["closes at no center distance", "driver.correct"]),
    "center distance too small": ('[driver]\nfamily = "ellipse"\nsemi_major_axis = 30.0\neccentricity = 0.3\n'
                                  '[pair]\ncenter_distance = 35.0\n',
                                  ["pair.center_distance = 35", "largest driver radius"]),
    "center distance does not close": ('[driver]\nfamily = "ellipse"\nsemi_major_axis = 30.0\neccentricity = 0.3\n'
                                       '[pair]\ncenter_distance = 70.0\n', ["does not close", "60.000000000",
                                                                        "leave pair.center_distance out"]),
    "eccentricity": ('[driver]\nfamily = "ellipse"\nsemi_major_axis = 30.0\neccentricity = 1.2\n',
                     ["driver.eccentricity", "1.2", "[0, 1)"]),
    "m12 breaks eq 2": ('[driver]\nfamily = "denatured_limacon"\nbase = 53.0\namplitude = 13.0\n'
                        'm11 = 1.5\nm12 = 0.375\n',
                        ["driver.m12", "0.375", "0.75", "breaks"]),
    "undercut module": ('[driver]\nfamily = "ellipse"\nsemi_major_axis = 30.0\neccentricity = 0.5\n'
                        '[pair]\nmodule = 4.0\nteeth = 12\n', ["module 4 undercuts", "below m / sin^2(alpha)"]),
    "teeth per lobe": ('[driver]\nfamily = "higher_order_ellipse"\nsemi_major_axis = 30.0\neccentricity = 0.2\n'
                       'order = 2\n[pair]\nmodule = 2.0\nteeth = 31\n',
                       ["pair.teeth = 31", "multiple of the driver order 2"]),
    "expression calls something else": ('[driver]\nfamily = "ratio"\nexpression = "__import__(\'os\')"\n'
                                        '[pair]\ncenter_distance = 50.0\n', ["driver.expression", "is not allowed"]),
    "expression not periodic": ('[driver]\nfamily = "ratio"\nexpression = "1 + phi / 10"\ncorrect = true\n'
                                '[pair]\ncenter_distance = 50.0\n', ["driver.ratio is not periodic"]),
    "expression goes negative": ('[driver]\nfamily = "ratio"\nexpression = "0.5 + cos(phi)"\ncorrect = true\n'
                                 '[pair]\ncenter_distance = 50.0\n',
                                 ["driver.expression = '0.5 + cos(phi)' reaches -0.5", "goes negative"]),
    "pole narrower than the grid": ('[driver]\nfamily = "ratio"\nexpression = "1 + 1e-12/(cos(phi) - 0.5403)**2"\n'
                                    'correct = true\n[pair]\ncenter_distance = 50.0\n',
                                    [f"at phi = {360 - np.degrees(np.arccos(0.5403)):.2f} deg", "from 0.001 to 1000"]),
    "pole through zero narrower than the grid": (
        '[driver]\nfamily = "ratio"\nexpression = "1 + 0.3*cos(phi) + 1e-9/(sin(phi) - 0.90929742)"\ncorrect = true\n'
        '[pair]\ncenter_distance = 50.0\n',
        [f"at phi = {180 - np.degrees(np.arcsin(0.90929742)):.2f} deg", "goes negative"]),
    "jump": ('[driver]\nfamily = "ratio"\nexpression = "1.5 + 0.1*sqrt(cos(phi)**2)/cos(phi)"\ncorrect = true\n'
             '[pair]\ncenter_distance = 50.0\n', ["not resolved near phi = 90.0000", "a pole or a jump"]),
    "expression as a number": ('[driver]\nfamily = "ratio"\nexpression = 1.5\n[pair]\ncenter_distance = 50.0\n',
                               ["driver.expression = 1.5", 'a formula of phi as text, e.g. "1.5"']),
    "key of another family": ('[driver]\nfamily = "ellipse"\nsemi_major_axis = 30.0\neccentricity = 0.3\nbase = 4.0\n',
                              ["driver.base", "no such field"]),
}


@pytest.fixture(scope="module")
def bad_runs(tmp_path_factory):
    """The command on every bad file of BAD, in this process with every warning an error (a warning the command
    let through would change the exit or its line): name -> (exit code, stderr). The interpreter's entry and its
    exit 2 are run in tests/cli/test_bad_input.py."""
    folder = tmp_path_factory.mktemp("bad_gear")
    runs = {}
    for number, (name, (text, _)) in enumerate(BAD.items()):
        path = folder / f"{number}.toml"
        path.write_text(text)
        stderr = io.StringIO()
        with warnings.catch_warnings(), contextlib.redirect_stderr(stderr), contextlib.redirect_stdout(io.StringIO()):
            warnings.simplefilter("error")
            runs[name] = (main(["gear", str(path)]), stderr.getvalue())
    return runs


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_gear_input(bad_runs, name):
    returncode, stderr = bad_runs[name]
    lines = stderr.strip().splitlines()
    assert returncode == 2 and len(lines) == 1 and "Traceback" not in stderr, stderr
    for fragment in BAD[name][1]:
        assert fragment in lines[0], (fragment, lines[0])

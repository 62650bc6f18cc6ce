"""Bad input, in a problem file or on the command line: one clear line naming the field, the value and what was
expected; exit 2."""
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

POSES = """
[[poses]]
x = 0.0
y = 0.0
angle_deg = 0.0
[[poses]]
x = 10.0
y = 2.0
angle_deg = 20.0
[[poses]]
x = 20.0
y = 1.0
angle_deg = 45.0
[[poses]]
x = 30.0
y = -3.0
angle_deg = 60.0
"""

CASES = {
    "two poses": ("[[poses]]\nx=0\ny=0\nangle_deg=0\n[[poses]]\nx=1\ny=0\nangle_deg=10\n",
                  ["poses", "2 poses", "at least 3"]),
    "no poses": ("title = 'x'\n", ["poses", "None", "array of tables"]),
    "duplicate": (POSES.replace("x = 10.0\ny = 2.0\nangle_deg = 20.0", "x = 0.0\ny = 0.0\nangle_deg = 360.0"),
                  ["poses[1]", "coincide", "poses[0]"]),
    "nan": (POSES.replace("y = 2.0", "y = nan"), ["poses[1].y", "nan", "finite number"]),
    "missing": (POSES.replace("angle_deg = 45.0", ""), ["poses[2].angle_deg", "missing"]),
    "text": (POSES.replace("x = 30.0", 'x = "thirty"'), ["poses[3].x", "thirty", "finite number"]),
    "unknown pose key": (POSES.replace("x = 20.0", "x = 20.0\nz = 1.0"), ["poses[2].z", "no such field", "angle_deg"]),
    "unknown table": (POSES + "[solver]\nmax_iter = 3\n", ["solver", "no such field"]),
    "translation": (POSES.replace("angle_deg = 20.0", "angle_deg = 0.0").replace("angle_deg = 45.0", "angle_deg = 0.0")
                    .replace("angle_deg = 60.0", "angle_deg = 0.0"), ["angle_deg", "pure translation"]),
    "phases length": (POSES + "[relative]\npivot = [0.0, 0.0]\nphases_deg = [0, 10]\n",
                      ["relative.phases_deg", "[0, 10]", "4 angles"]),
    "relative translation": (POSES + "[relative]\npivot = [5.0, 5.0]\nphases_deg = [0, 20, 45, 60]\n",
                             ["angle_deg", "relative to the turning link", "pure translation"]),
    "bad pivot": (POSES + "[relative]\npivot = [0.0]\nphases_deg = [0, 1, 2, 3]\n", ["relative.pivot", "[x, y]"]),
    "three poses without choice": ("[[poses]]" + "[[poses]]".join(POSES.split("[[poses]]")[1:4]),
                                   ["three_poses", "circle_points or center_points"]),
    "three_poses with four": (POSES + "[three_poses]\ncircle_points = [[1.0, 2.0]]\n", ["three_poses", "exactly 3"]),
    "samples": (POSES + "[search]\nsamples = 3\n", ["search.samples", "3", "16 to 200000"]),
    "radius": (POSES + "[search]\nradius_mm = -5.0\n", ["search.radius_mm", "-5.0", "positive"]),
    "angle beyond a turn": (POSES.replace("angle_deg = 60.0", "angle_deg = 420.0"),
                            ["poses[].angle_deg", "420.0", "within one turn"]),
    "not toml": ("[[poses]\nx=", ["not valid TOML"]),
    "label not text": (POSES.replace("x = 10.0", "label = {a = 1}\nx = 10.0"),
                       ["poses[1].label", "{'a': 1}", "text of at most 40 characters"]),
    "label too long": (POSES.replace("x = 10.0", f"label = '{'P' * 41}'\nx = 10.0"),
                       ["poses[1].label", "PPPP", "at most 40 characters"]),
    "label with a control character": (POSES.replace("x = 10.0", 'label = "P\\f2"\nx = 10.0'),
                                       ["poses[1].label", "without control characters"]),
    "title not text": ("title = 5\n" + POSES, ["title = 5", "text of at most 200 characters"]),
}


def _run(*args, cwd=ROOT):
    return subprocess.run([sys.executable, "-m", "transplanter", *args], capture_output=True, text=True, cwd=cwd)


@pytest.mark.parametrize("name", sorted(CASES))
def test_bad_input_gives_one_clear_line(tmp_path, name):
    text, expected = CASES[name]
    path = tmp_path / "problem.toml"
    path.write_text(text)
    run = _run("burmester", str(path))
    assert run.returncode == 2, run.stderr
    lines = run.stderr.strip().splitlines()
    assert len(lines) == 1 and "Traceback" not in run.stderr, run.stderr
    assert lines[0].startswith(f"transplanter: error: {path}")
    for fragment in expected:
        assert fragment in lines[0], (fragment, lines[0])
    assert run.stdout == ""


def test_missing_file():
    run = _run("burmester", "no/such/file.toml")
    assert run.returncode == 2
    assert run.stderr.strip() == "transplanter: error: no/such/file.toml: no such file"


RADIANS = (POSES.replace("angle_deg = 20.0", "angle_deg = 0.35").replace("angle_deg = 45.0", "angle_deg = 0.78")
           .replace("angle_deg = 60.0", "angle_deg = 1.05"))


def test_radians_in_a_degree_field_warn(tmp_path):
    path = tmp_path / "problem.toml"
    path.write_text(RADIANS)
    run = _run("burmester", str(path))
    assert run.returncode == 0
    assert run.stderr.count("\n") == 1 and "look like radians" in run.stderr and "poses[].angle_deg" in run.stderr


def test_a_warning_of_a_failed_run_is_folded_into_its_one_line(tmp_path):
    path = tmp_path / "problem.toml"
    path.write_text(RADIANS + "[search]\nradius_mm = 0.001\n")
    run = _run("burmester", str(path))
    assert run.returncode == 1
    assert run.stderr.count("\n") == 1 and run.stderr.startswith("transplanter: failed: ")
    assert "no dyad found" in run.stderr and "; warning: " in run.stderr and "look like radians" in run.stderr


@pytest.mark.parametrize("argv, named", [(["fivebar", "examples/vegetable_planting.toml", "--pick", "two"], "--pick"),
                                         (["bogus"], "bogus"), (["gear"], "file"),
                                         (["fivebar", "examples/vegetable_planting.toml", "--design",
                                           "examples/vegetable_planting_table4.toml", "--pick", "2"], "--pick"),
                                         (["parallelogram", "examples/onion_transplanter.toml", "--pick", "2",
                                           "--design", "examples/onion_published.toml"], "--design")])
def test_bad_command_line_gives_one_line_and_exit_2(argv, named, capsys):
    from transplanter.cli import main

    with pytest.raises(SystemExit) as stop:
        main(argv)
    err = capsys.readouterr().err
    assert stop.value.code == 2 and err.count("\n") == 1 and named in err and "Traceback" not in err

"""The burmester command on the bundled examples: JSON fields checked independently, figures, reports, the
many-poses table."""
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from transplanter.burmester.problem import load_problem
from transplanter.geometry.dyad import verify_dyad
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[2]


def _json(example):
    run = subprocess.run([sys.executable, "-m", "transplanter", "burmester", f"examples/{example}", "--json"],
                         capture_output=True, text=True, cwd=ROOT, check=True)
    return json.loads(run.stdout)


def _carried(pose_1, pose, point):
    """Where a body point at ``point`` in pose 1 is in ``pose``: rotate about the reference point, then move."""
    turn = np.radians(pose[2] - pose_1[2])
    offset = np.asarray(point) - pose_1[:2]
    return pose[:2] + [np.cos(turn) * offset[0] - np.sin(turn) * offset[1],
                       np.sin(turn) * offset[0] + np.cos(turn) * offset[1]]


def test_json_of_five_poses_checks_out_independently():
    """Each reported dyad keeps its length through the file's poses (carried here by hand), and two of them
    are the crank (0, 0)-(39.3923, 6.9459), 40 mm, and the rocker (100, 0)-(92.4502, 79.6430), 80 mm, of the
    crank-rocker the example was made from (poses rounded to 1e-4)."""
    report = _json("burmester_5poses.toml")
    rows = read_toml(ROOT / "examples/burmester_5poses.toml")["poses"]
    poses = np.array([[p["x"], p["y"], p["angle_deg"]] for p in rows])
    assert len(report["dyads"]) == 4
    for dyad in report["dyads"]:
        assert set(dyad) >= {"center", "circle", "length", "max_residual"}
        lengths = [np.linalg.norm(_carried(poses[0], pose, dyad["circle"]) - dyad["center"]) for pose in poses]
        assert np.ptp(lengths) < 1e-9 * report["pose_scale_mm"]
        assert dyad["length"] == pytest.approx(lengths[0], rel=1e-12)
    for center, circle, length in (([0, 0], [39.3923, 6.9459], 40.0), ([100, 0], [92.4502, 79.6430], 80.0)):
        found = min(report["dyads"], key=lambda d: np.linalg.norm(np.subtract(d["center"], center)))
        assert np.linalg.norm(np.subtract(found["center"], center)) < 1e-2
        assert np.linalg.norm(np.subtract(found["circle"], circle)) < 1e-2
        assert found["length"] == pytest.approx(length, abs=1e-2)


def test_relative_center_is_the_link_fixed_pivot_in_pose_1():
    report = _json("burmester_relative.toml")
    problem = load_problem(ROOT / "examples/burmester_relative.toml")
    assert report["relative"]["phases_deg"] == [0.0, -18.0, -50.0, -90.0]
    assert report["max_residual"] < 1e-9
    for dyad in report["dyads"][::40]:
        assert verify_dyad(problem.poses, dyad["center"], dyad["circle"], problem.link).max_residual < 1e-9


def test_plot_and_report_files(tmp_path):
    run = subprocess.run([sys.executable, "-m", "transplanter", "burmester", "examples/burmester_4poses.toml",
                          "--out", str(tmp_path / "out"), "--plot", str(tmp_path / "fig.png")],
                         capture_output=True, text=True, cwd=ROOT)
    assert run.returncode == 0, run.stderr
    for name in ("out/report.md", "out/report.json", "out/burmester.png", "fig.png"):
        assert (tmp_path / name).stat().st_size > 1000
    assert (tmp_path / "fig.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    report = json.loads((tmp_path / "out/report.json").read_text())
    assert len(report["dyads"]) > 500 and len(report["circle_curve_dyads"]) > 500
    assert "center-point" in (tmp_path / "out/report.md").read_text()
    assert "dyads:" in run.stdout


def test_many_poses_table():
    run = subprocess.run([sys.executable, "-m", "transplanter", "burmester", "examples/burmester_7poses.toml"],
                         capture_output=True, text=True, cwd=ROOT, check=True)
    assert "least-squares" in run.stdout and "RMS length error" in run.stdout

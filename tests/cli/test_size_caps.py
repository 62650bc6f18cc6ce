"""Sizes a user sets are bounded before the work: lists past their cap are refused in one line that names the
field, the count and the cap (exit 2); under the cap the work is linear (the periodic spline of a sampled ratio
is solved as a sparse cyclic system, not a dense n-by-n one)."""
from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from transplanter.burmester.problem import LARGEST_POSE_COUNT
from transplanter.cam.problem import LARGEST_SEGMENT_COUNT
from transplanter.cli import main
from transplanter.fivebar.problem import MOST_CONTROL_POINTS
from transplanter.gears.composite_fields import LARGEST_SEGMENT_COUNT as LARGEST_COMPOSITE_SEGMENTS
from transplanter.gears.pitch_curves import PeriodicSpline
from transplanter.gears.problem import LARGEST_SAMPLE_COUNT
from transplanter.reverse.problem import LARGEST_POINT_COUNT

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def _one_line(capsys, argv) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    return err


def _replaced(text: str, start: str, end: str, new: str) -> str:
    """``text`` with the part from ``start`` up to and including the first ``end`` after it replaced by ``new``."""
    first = text.index(start)
    return text[:first] + new + text[text.index(end, first) + len(end):]


def _ratio_angles(count: int) -> str:
    return ", ".join(f"{v:.6f}" for v in np.arange(count) * 360 / count)


def _path_points(count: int) -> str:
    angle = np.linspace(0, 2 * np.pi, count, endpoint=False)
    return ", ".join(f"[{44 * np.sin(t):.6f}, {-161.5 + 93 * np.cos(t):.6f}]" for t in angle)


@pytest.mark.parametrize("command, example, key, end, cap, rows, field, what", [
    ("gear", "gear_ratio.toml", "phi_deg", "]\n", LARGEST_SAMPLE_COUNT, _ratio_angles, "driver.phi_deg", "numbers"),
    ("reverse", "rice_hoe_reverse.toml", "points", "\n]\n", LARGEST_POINT_COUNT, _path_points, "trajectory.points",
     "points"),
])
def test_a_list_past_its_cap(tmp_path, capsys, command, example, key, end, cap, rows, field, what):
    """A sampled ratio's angles, a reverse path's points: one past the cap is refused before the work."""
    problem = tmp_path / "problem.toml"
    problem.write_text(_replaced((EXAMPLES / example).read_text(), f"{key} = [", end,
                                 f"{key} = [{rows(cap + 1)}]\n"))
    err = _one_line(capsys, [command, str(problem)])
    assert f"{field} = '{cap + 1} {what}': expected at most {cap} {what}" in err


def test_burmester_poses_past_their_cap(tmp_path, capsys):
    count = LARGEST_POSE_COUNT + 1
    problem = tmp_path / "poses.toml"
    problem.write_text("".join(f"[[poses]]\nx = {k}.0\ny = {k % 7}.0\nangle_deg = {k % 11}.0\n" for k in range(count)))
    err = _one_line(capsys, ["burmester", str(problem)])
    assert f"poses = '{count} poses': expected at most {LARGEST_POSE_COUNT} poses" in err


def test_cam_segments_past_their_cap(tmp_path, capsys):
    """A turn cut into one more rise than the cap (and a return to the base): refused before the work."""
    count = LARGEST_SEGMENT_COUNT
    text = (EXAMPLES / "cam_flat_faced.toml").read_text()
    rows = "".join(f'[[segments]]\nkind = "rise"\nangle_deg = {180 / count!r}\nlaw = "cycloidal"\nlift = 0.01\n\n'
                   for _ in range(count))
    rows += f'[[segments]]\nkind = "return"\nangle_deg = 180.0\nlaw = "cycloidal"\nlift = {0.01 * count!r}\n\n'
    problem = tmp_path / "cam.toml"
    problem.write_text(text[:text.index("[[segments]]")] + rows + text[text.index("[limits]"):])
    err = _one_line(capsys, ["cam", str(problem)])
    assert f"segments = '{count + 1} segments': expected at most {count} segments" in err


def _arcs(count: int, splines: int = 0, samples: int = 0) -> str:
    """A composite circle of radius 20 mm cut into ``count`` pieces, the first ``splines`` of them splines of
    ``samples`` radii each."""
    rows = ""
    for k in range(count):
        rows += f'[[driver.segments]]\nphi_deg = [{360 * k / count!r}, {360 * (k + 1) / count!r}]\n'
        rows += (f'kind = "spline"\nradius = {[20.0] * samples}\n' if k < splines
                 else 'kind = "arc"\ncenter = [0.0, 0.0]\nradius = 20.0\n')
    return '[driver]\nfamily = "composite"\n' + rows


def test_composite_segments_past_their_cap(tmp_path, capsys):
    count = LARGEST_COMPOSITE_SEGMENTS + 1
    problem = tmp_path / "composite.toml"
    problem.write_text(_arcs(count))
    err = _one_line(capsys, ["gear", str(problem)])
    assert f"driver.segments = '{count} segments': expected at most {count - 1} segments" in err


def test_composite_spline_samples_past_their_cap_together(tmp_path, capsys):
    """Two spline segments of half the cap and one more each: each is within the cap, together they are past it."""
    half = LARGEST_SAMPLE_COUNT // 2 + 1
    problem = tmp_path / "composite.toml"
    problem.write_text(_arcs(4, splines=2, samples=half))
    err = _one_line(capsys, ["gear", str(problem)])
    assert f"driver.segments = '{2 * half} spline samples': expected at most {LARGEST_SAMPLE_COUNT}" in err


def test_return_points_past_the_spline_name_their_own_limit(tmp_path, capsys):
    count = MOST_CONTROL_POINTS - 3
    text = (EXAMPLES / "vegetable_planting.toml").read_text()
    rows = "".join(f"[[return_points]]\nx = {-200 + k * 0.5}\ny = {-120 - k * 0.25}\n\n" for k in range(count))
    problem = tmp_path / "many.toml"
    problem.write_text(re.sub(r"\[\[return_points\]\]\n(?:[^\[\n][^\n]*\n|\n)*", "", text) + "\n" + rows)
    err = _one_line(capsys, ["fivebar", str(problem)])
    assert f"return_points = '{count} points': expected at most {MOST_CONTROL_POINTS - 4} (the relative angle" in err


@pytest.mark.parametrize("count", [3, 4, 9, 200])
def test_the_sparse_periodic_spline_equals_scipys_periodic_cubic_spline(count):
    """An independent reference: scipy's periodic CubicSpline through the same unevenly spaced samples gives the
    same values, slopes and bends (three knots put the cyclic corners beside the diagonal, where entries sum)."""
    rng = np.random.default_rng(count)
    knots = np.sort(rng.uniform(0, 2 * np.pi, count))
    values = 1 + rng.uniform(0, 1, count)
    reference = CubicSpline(np.r_[knots, knots[0] + 2 * np.pi], np.r_[values, values[0]], bc_type="periodic")
    at = np.mod(knots[0] + np.linspace(0, 2 * np.pi, 997, endpoint=False), 2 * np.pi)
    unwrapped = np.where(at < knots[0], at + 2 * np.pi, at)
    for order, ours in enumerate(PeriodicSpline(knots, values).evaluate(at)):
        expected = reference(unwrapped, order)
        assert np.allclose(ours, expected, rtol=1e-9, atol=1e-9 * np.abs(expected).max()), order

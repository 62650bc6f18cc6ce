"""Time the Burmester solvers against plain numpy/scipy baselines, in one run.

    python bench/bench_burmester.py

Targets (issue 2, 2-core machine, after imports): 5-pose solve under 5 ms, 4-pose trace
(2,000 samples) under 20 ms. Baselines:
- 5 poses: scipy.optimize.least_squares from 64 random starts (what a one-off script does;
  unlike the resultant it can miss solutions).
- 4 poses: a per-line numpy loop: on each of the 2,000 lines through the pole, the cubic
  restricted to the line is fitted from four determinant values and solved with np.roots,
  and each center gets its circle point by np.linalg.lstsq.
"""
from __future__ import annotations

import dataclasses
import sys
import time
from pathlib import Path

import numpy as np
from scipy.optimize import least_squares

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from ground_truth import dyad_poses  # noqa: E402
from transplanter.burmester.five_poses import burmester_points  # noqa: E402
from transplanter.burmester.four_poses import trace_dyads  # noqa: E402
from transplanter.geometry.poses import Frame, carry, pole, rotation  # noqa: E402
from transplanter.burmester.problem import load_problem  # noqa: E402
from transplanter.burmester.synthesis import synthesize  # noqa: E402

SAMPLES = 2000


def best_time(function, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return min(times)


def _rows(poses, center):
    """Eq (1) rows affine in the circle point, written out by hand for the baseline."""
    rows = []
    for pose in poses[1:]:
        q = rotation(pose[2] - poses[0, 2])
        shift = pose[:2] - q @ poses[0, :2]
        # |q m + shift - g|^2 - |m - g|^2 = 2 m.(q^T (shift - g) + g) + |shift - g|^2 - |g|^2
        rows.append([*(2 * (q.T @ (shift - center) + center)), (shift - center) @ (shift - center) - center @ center])
    return np.array(rows)


def baseline_trace(poses, samples=SAMPLES, radius=10.0):
    pivot = pole(poses[0], poses[int(np.argmax(1 - np.cos(poses[1:, 2] - poses[0, 2]))) + 1])
    centers, circles = [], []
    probe = np.array([-1.0, -0.5, 0.5, 1.0])
    for angle in np.pi * np.arange(samples) / samples:
        direction = np.array([np.cos(angle), np.sin(angle)])
        values = [np.linalg.det(_rows(poses, pivot + t * direction)) for t in probe]
        cubic = np.polyfit(probe, values, 3)
        for t in np.roots(cubic):
            if abs(t.imag) < 1e-9 and abs(t.real) > 1e-9:
                g = pivot + t.real * direction
                if np.hypot(*g) <= radius:
                    rows = _rows(poses, g)
                    centers.append(g)
                    circles.append(np.linalg.lstsq(rows[:, :2], -rows[:, 2], rcond=None)[0])
    return np.array(centers), np.array(circles)


def baseline_five(poses, rng, starts=64):
    def residual(z):
        d = np.linalg.norm(carry(poses, z[2:]) - z[:2], axis=1)
        return d[1:] - d[0]
    found = []
    for _ in range(starts):
        fit = least_squares(residual, rng.normal(size=4) * 2, method="lm")
        if np.abs(fit.fun).max() < 1e-10 and all(np.linalg.norm(fit.x - f) > 1e-6 for f in found):
            found.append(fit.x)
    return found


def main():
    rng = np.random.default_rng(7)
    poses4, _, _ = dyad_poses(rng, 4)
    local4 = Frame.of(poses4).local_poses(poses4)
    trace_dyads(local4, SAMPLES, 10.0)
    ours = best_time(lambda: trace_dyads(local4, SAMPLES, 10.0), 20)
    base = best_time(lambda: baseline_trace(local4), 2)
    print(f"4-pose center-point trace, {SAMPLES} lines: transplanter {ours * 1e3:.2f} ms, "
          f"numpy loop {base * 1e3:.1f} ms, ratio {base / ours:.0f}x  (target < 20 ms)")
    problem = dataclasses.replace(load_problem(ROOT / "examples/burmester_4poses.toml"), samples=SAMPLES)
    synthesize(problem)
    full = best_time(lambda: synthesize(problem), 10)
    print(f"4-pose synthesis on the seed 000 example, both curves, {SAMPLES} lines each, every dyad verified: "
          f"{full * 1e3:.1f} ms")

    poses5, _, _ = dyad_poses(rng, 5)
    local5 = Frame.of(poses5).local_poses(poses5)
    burmester_points(local5)
    ours = best_time(lambda: burmester_points(local5), 50)
    base = best_time(lambda: baseline_five(local5, np.random.default_rng(0)), 3)
    print(f"5-pose Burmester points: transplanter {ours * 1e3:.2f} ms ({len(burmester_points(local5)[0])} found), "
          f"scipy 64-start least_squares {base * 1e3:.1f} ms ({len(baseline_five(local5, np.random.default_rng(0)))} found), "
          f"ratio {base / ours:.0f}x  (target < 5 ms)")
    problem5 = load_problem(ROOT / "examples/burmester_5poses.toml")
    full = best_time(lambda: synthesize(problem5), 20)
    print(f"5-pose synthesis of examples/burmester_5poses.toml, verified: {full * 1e3:.2f} ms")


if __name__ == "__main__":
    main()

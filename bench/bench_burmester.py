"""Time the Burmester solvers against plain numpy/scipy baselines, in one run.

    python bench/bench_burmester.py

Targets (2-core machine, after imports): 5-pose solve under 5 ms, 4-pose trace
(2,000 samples) under 20 ms. Baselines:
- 5 poses: Burmester's classical construction, numerically: the Burmester points are where the
  center-point curves of poses 1-2-3-4 and 1-2-3-5 meet. Both pass through the pole P12; on each of
  ``SAMPLES`` lines through it the first curve's cubic (fitted from four determinant values, the
  pole's root divided out) gives two points, the second curve's determinant is evaluated there, its
  sign changes between neighbouring lines are refined by scipy's brentq, and the points that meet
  eq (1) for all five poses are kept (the other common points of the two curves, the poles P13 and
  P23, fail it). Also, as a one-off script would do it: scipy.optimize.least_squares from random
  starts, stopping as soon as it has as many distinct solutions as the package found (a multistart
  cannot know it has them all, so this rule favours it), at most 64 starts.
- 4 poses: the same mathematics vectorised in numpy: on all 2,000 lines through the pole at
  once, the cubic restricted to the line is fitted from four determinant values, its roots
  are the eigenvalues of its companion matrix, and each center gets its circle point by least
  squares (normal equations).
"""
from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np
from best_time import best_time  # bench/ is the script's own folder
from scipy.optimize import brentq, least_squares

from transplanter.burmester.five_poses import burmester_points
from transplanter.burmester.four_poses import trace_dyads
from transplanter.burmester.problem import load_problem
from transplanter.burmester.synthesis import synthesize
from transplanter.geometry.poses import Frame, carry, pole, rotation

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "burmester"))

from ground_truth import dyad_poses  # noqa: E402  (tests/burmester/ joins sys.path just above)

SAMPLES = 2000



def _rows(poses, centers):
    """Eq (1) rows affine in the circle point, written out by hand for the baseline: (k, poses - 1, 3)."""
    turns = rotation(poses[1:, 2] - poses[0, 2])                             # (j, 2, 2)
    shifts = poses[1:, :2] - turns @ poses[0, :2]                            # (j, 2)
    offset = shifts[None] - centers[:, None]                                 # (k, j, 2)
    # |q m + shift - g|^2 - |m - g|^2 = 2 m.(q^T (shift - g) + g) + |shift - g|^2 - |g|^2
    linear = 2 * (np.einsum("jba,kjb->kja", turns, offset) + centers[:, None])
    constant = np.sum(offset**2, axis=-1) - np.sum(centers**2, axis=-1)[:, None]
    return np.concatenate([linear, constant[..., None]], axis=-1)


def baseline_trace(poses, samples=SAMPLES, radius=10.0):
    """The same mathematics as the package, vectorised in numpy: on every line through the pole the
    cubic restricted to the line is fitted from four determinant values, its roots are the
    eigenvalues of its companion matrix, and each center gets its circle point by least squares."""
    pivot = pole(poses[0], poses[int(np.argmax(1 - np.cos(poses[1:, 2] - poses[0, 2]))) + 1])
    probe = np.array([-1.0, -0.5, 0.5, 1.0])
    angles = np.pi * np.arange(samples) / samples
    directions = np.stack([np.cos(angles), np.sin(angles)], -1)
    points = pivot + probe[None, :, None] * directions[:, None]              # (lines, 4, 2)
    values = np.linalg.det(_rows(poses, points.reshape(-1, 2))).reshape(samples, 4)
    cubic = np.polyfit(probe, values.T, 3).T                                 # (lines, 4), highest power first
    companion = np.zeros((samples, 3, 3))
    companion[:, 0] = -cubic[:, 1:] / cubic[:, :1]
    companion[:, 1, 0] = companion[:, 2, 1] = 1.0
    roots = np.linalg.eigvals(companion)                                     # (lines, 3)
    keep = (np.abs(roots.imag) < 1e-9) & (np.abs(roots.real) > 1e-9)
    centers = pivot + roots.real[..., None] * directions[:, None]
    keep &= np.hypot(centers[..., 0], centers[..., 1]) <= radius
    centers = centers[keep]
    rows = _rows(poses, centers)
    a, b = rows[..., :2], rows[..., 2]
    normal = np.swapaxes(a, 1, 2)
    circles = np.linalg.solve(normal @ a, -(normal @ b[..., None]))[..., 0]
    return centers, circles


def _circle_points(poses, centers):
    """Circle points by least squares on the rows of eq (1) (normal equations), one per center."""
    rows = _rows(poses, centers)
    a, b = rows[..., :2], rows[..., 2]
    normal = np.swapaxes(a, 1, 2)
    return np.linalg.solve(normal @ a, -(normal @ b[..., None]))[..., 0]


def classical_five(poses, samples=SAMPLES, tolerance=1e-9):
    """The Burmester points of five poses as the meeting points of the center-point curves of poses
    1-2-3-4 and 1-2-3-5, found on lines through their common pole P12 (module docstring); (centers,
    circles) meeting eq (1) for every pose to ``tolerance`` of the poses' size."""
    pivot = pole(poses[0], poses[1])
    probe = np.array([-1.0, -0.5, 0.5, 1.0])
    first, second = [0, 1, 2], [0, 1, 3]          # rows of poses 2, 3, 4 and of poses 2, 3, 5

    def points(angle):
        """The first curve's two points (other than P12) on the line at ``angle``: (2, 2), NaN where complex."""
        direction = np.stack([np.cos(angle), np.sin(angle)], -1)
        probes = pivot + probe[..., None] * direction[..., None, :]
        values = np.linalg.det(_rows(poses, probes.reshape(-1, 2))[:, first]).reshape(-1, 4)
        cubic = np.polyfit(probe, values.T, 3).T.reshape(*np.shape(angle), 4)
        a, b, c = cubic[..., 0], cubic[..., 1], cubic[..., 2]          # a t^3 + b t^2 + c t (+ d ~ 0: P12)
        root = np.sqrt(b**2 - 4 * a * c + 0j)
        t = np.stack([(-b - root) / (2 * a), (-b + root) / (2 * a)], -1)
        t = np.where(np.abs(t.imag) < 1e-12, t.real, np.nan)
        return pivot + t[..., None] * direction[..., None, :]

    def other_curve(angle, branch):
        point = points(np.atleast_1d(angle))[..., branch, :]
        return float(np.linalg.det(_rows(poses, point.reshape(-1, 2))[:, second])[0])

    angles = np.pi * np.arange(samples + 1) / samples
    on_first = points(angles)                                        # (samples + 1, 2, 2)
    with np.errstate(invalid="ignore"):                              # NaN: no real point on that line
        values = np.linalg.det(_rows(poses, on_first.reshape(-1, 2))[:, second]).reshape(samples + 1, 2)
    found = []
    for branch in range(2):
        change = np.flatnonzero(values[:-1, branch] * values[1:, branch] < 0)
        for k in change:
            angle = brentq(other_curve, angles[k], angles[k + 1], args=(branch,), xtol=1e-15)
            found.append(points(np.atleast_1d(angle))[0, branch])
    centers = np.array(found).reshape(-1, 2)
    circles = _circle_points(poses, centers)
    size = np.abs(poses[:, :2] - poses[:, :2].mean(axis=0)).max()
    lengths = np.linalg.norm(carry(poses, circles) - centers[:, None], axis=-1)
    keep = np.abs(lengths - lengths[:, :1]).max(axis=1) <= tolerance * size
    return centers[keep], circles[keep]


def baseline_five(poses, rng, wanted, starts=64):
    """scipy least_squares on eq (1) from random starts, stopping once ``wanted`` distinct solutions
    are found (the package's count: at most 4 real Burmester points exist) or the starts run out."""
    def residual(z):
        d = np.linalg.norm(carry(poses, z[2:]) - z[:2], axis=1)
        return d[1:] - d[0]
    found, tried = [], 0
    while len(found) < wanted and tried < starts:
        tried += 1
        fit = least_squares(residual, rng.normal(size=4) * 2, method="lm")
        if np.abs(fit.fun).max() < 1e-10 and all(np.linalg.norm(fit.x - f) > 1e-6 for f in found):
            found.append(fit.x)
    return found, tried


def main():
    rng = np.random.default_rng(7)
    poses4, _, _ = dyad_poses(rng, 4)
    local4 = Frame.of(poses4).local_poses(poses4)
    centers, _ = trace_dyads(local4, SAMPLES, 10.0)
    base_centers, _ = baseline_trace(local4)
    ours = best_time(lambda: trace_dyads(local4, SAMPLES, 10.0), 20)[0]
    base = best_time(lambda: baseline_trace(local4), 20)[0]
    print(f"4-pose center-point trace, {SAMPLES} lines: transplanter {ours * 1e3:.2f} ms ({len(centers)} dyads), "
          f"baseline (the same per-line cubic, vectorised in numpy) {base * 1e3:.2f} ms ({len(base_centers)} dyads), "
          f"ratio {base / ours:.1f}x  (target < 20 ms)")
    problem = dataclasses.replace(load_problem(ROOT / "examples/burmester_4poses.toml"), samples=SAMPLES)
    synthesize(problem)
    full = best_time(lambda: synthesize(problem), 10)[0]
    print(f"4-pose synthesis on the Wang et al. 2025 example, both curves, {SAMPLES} lines each, every dyad verified: "
          f"{full * 1e3:.1f} ms")

    poses5, _, _ = dyad_poses(rng, 5)
    local5 = Frame.of(poses5).local_poses(poses5)
    wanted = len(burmester_points(local5)[0])
    ours, (centers, _) = best_time(lambda: burmester_points(local5), 50)
    classical, (their_centers, _) = best_time(lambda: classical_five(local5), 50)
    apart = max(np.linalg.norm(their_centers - c, axis=1).min() for c in np.asarray(centers)) if wanted else 0.0
    print(f"5-pose Burmester points: transplanter {ours * 1e3:.2f} ms ({wanted} found); baseline Burmester's "
          f"construction (the center-point curves of poses 1-2-3-4 and 1-2-3-5 met on {SAMPLES} lines through "
          f"P12, brentq) {classical * 1e3:.2f} ms ({len(their_centers)} found, centers within {apart:.1e} of ours); "
          f"ratio {classical / ours:.1f}x  (target < 5 ms)")
    base = best_time(lambda: baseline_five(local5, np.random.default_rng(0), wanted), 3)[0]
    found, tried = baseline_five(local5, np.random.default_rng(0), wanted)
    print(f"  and a one-off script's scipy least_squares from random starts until it has found as many "
          f"({len(found)} found in {tried} starts): {base * 1e3:.1f} ms; ratio {base / ours:.0f}x")
    problem5 = load_problem(ROOT / "examples/burmester_5poses.toml")
    full = best_time(lambda: synthesize(problem5), 20)[0]
    print(f"5-pose synthesis of examples/burmester_5poses.toml, verified: {full * 1e3:.2f} ms")


if __name__ == "__main__":
    main()

"""Speed of the reverse design against a scipy baseline, in one run.

    python bench/bench_reverse.py

Both start from the 19 control points of examples/rice_hoe_reverse.toml and end with
verified pitch curves of the four-gear train (square-root split with correction factor); the package also
cuts the train's whole teeth and checks their mesh (the baseline does not), without the tolerance analysis.

- Package: ``synthesize`` (closed-form inverse kinematics with branch switches, rates to
  third order from the generated derivation, panel polynomials, gear pairs, rolling check).
- Baseline, the sampled way the papers describe, with scipy: the path from scipy's periodic
  BSpline at N samples, the same closed-form inverse kinematics and branch switches at the
  sampled extremes, the ratio by finite differences of the sampled angles (the rice-transplanter paper's
  "difference method"), the split and correction factor by Simpson's rule, pitch curves
  r = a / (1 + I) on the grid, and the round trip by equal arc lengths with linear
  interpolation. (The rice-transplanter paper's point-by-point Newton has the Jacobian determinant s l sin(gamma),
  zero where the arm straightens or folds, which these paths must do: both use the closed form.)

The target is under 2 s for the package's pitch curves (before teeth were cut: today it is over, see
docs/reverse.md). The baseline is run at three sample counts:
its time, and how far its round trip stays from the path, against the package's.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
from fresh_process import cli_run  # bench/ is the script's own folder
from scipy.integrate import cumulative_trapezoid, simpson
from scipy.interpolate import BSpline

from transplanter.reverse.problem import load_problem
from transplanter.reverse.synthesis import synthesize

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "rice_hoe_reverse.toml"
SAMPLES = 3600


def baseline(control: np.ndarray, carrier: float, arm: float, direction: int, start_branch: int, centers,
             samples: int):
    """The sampled approach: returns (largest round-trip miss in mm, stage 1 closure error in rad);
    ``carrier`` and ``arm`` are the lengths s and l of the reverse-gear-design paper."""
    n = len(control)
    path = BSpline(np.arange(-3, n + 4) / n, np.r_[control, control[:3]], 3, extrapolate="periodic")
    u = np.linspace(0, 1, samples, endpoint=False)
    points = path(np.mod(u - 1 / n, 1))                              # scipy's segment k is the package's k + 1
    r, phi3 = np.hypot(*points.T), np.arctan2(points[:, 1], points[:, 0])
    elbow = np.arccos(np.clip((carrier**2 + r**2 - arm**2) / (2 * carrier * r), -1, 1))
    # the branch changes where the arm straightens or folds
    switches = sorted([int(np.argmax(r)), int(np.argmin(r))])
    branch = start_branch * np.where((np.arange(samples) > switches[0]) & (np.arange(samples) <= switches[1]), -1, 1)
    if switches[0] == 0:
        branch = start_branch * np.where(np.arange(samples) <= switches[1], 1, -1)
    theta = np.unwrap(phi3 + branch * elbow)
    psi = np.unwrap(np.arctan2(points[:, 1] - carrier * np.sin(theta), points[:, 0] - carrier * np.cos(theta)))
    c = direction * (theta - theta[0])
    chi = -direction * ((psi - theta) - (psi[0] - theta[0]))
    chi_rate = np.gradient(chi, c)                                 # the difference method
    grid = np.linspace(0, 2 * np.pi, samples + 1)
    rate = np.interp(grid, np.r_[c, 2 * np.pi], np.r_[chi_rate, chi_rate[0]])
    k = 2 * np.pi / simpson(np.sqrt(rate), x=grid)
    first, second = 1 / (np.sqrt(rate) * k), k / np.sqrt(rate)     # I1, I2 corrected
    a1, a2 = centers
    sun = a1 / (1 + first)
    psi_turn = cumulative_trapezoid(1 / first, grid, initial=0)   # intermediate angle against the sun's
    def arc(radius, angle):
        return cumulative_trapezoid(np.hypot(radius, np.gradient(radius, angle)), angle, initial=0)
    psi_rolled = np.interp(arc(sun, grid), arc(a1 - sun, psi_turn), psi_turn)
    planet_turn = cumulative_trapezoid(1 / second, psi_turn, initial=0)
    chi_rolled = np.interp(psi_rolled, psi_turn, planet_turn)
    tip_theta = theta[0] + direction * grid
    tip_gamma = (psi[0] - theta[0]) - direction * chi_rolled
    tips = np.c_[carrier * np.cos(tip_theta) + arm * np.cos(tip_theta + tip_gamma),
                 carrier * np.sin(tip_theta) + arm * np.sin(tip_theta + tip_gamma)]
    target = np.c_[np.interp(grid, np.r_[c, 2 * np.pi], np.r_[points[:, 0], points[0, 0]]),
                   np.interp(grid, np.r_[c, 2 * np.pi], np.r_[points[:, 1], points[0, 1]])]
    return np.linalg.norm(tips - target, axis=1).max(), psi_turn[-1] - 2 * np.pi


def main():
    problem = load_problem(EXAMPLE)
    synthesize(problem, tolerance=False)                       # warm: casadi/numpy imports, generated code
    start = time.perf_counter()
    result = synthesize(problem, tolerance=False)
    package = time.perf_counter() - start
    print(f"package  synthesize (whole teeth cut and mesh-checked too, no tolerance analysis): {package:.3f} s; "
          f"round trip {result.verification.max_error_mm:.2e} mm, "
          f"closure errors {result.train.stage_one.closure_error:.1e}, {result.train.stage_two.closure_error:.1e} rad")

    for samples in (3600, 36000, 360000):
        start = time.perf_counter()
        miss, closure = baseline(result.trajectory.control, result.motion.carrier_length, result.motion.arm_length,
                                 problem.direction, result.motion.start_branch, result.train.center_distances, samples)
        base = time.perf_counter() - start
        print(f"baseline with {samples:>6} samples: {base:.3f} s "
              f"(the package takes {package / base:.0f}x as long); round trip {miss:.2e} mm "
              f"({miss / result.verification.max_error_mm:.0e}x the package's), stage 1 closure "
              f"{closure:.1e} rad")

    print(f"CLI in a fresh process, with report and figures: {cli_run('reverse', str(EXAMPLE))[0]:.2f} s")

if __name__ == "__main__":
    main()

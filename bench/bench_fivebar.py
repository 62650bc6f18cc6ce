"""Speed of the five-bar main job (issue 3), against baselines, in one run.

    python bench/bench_fivebar.py

1. Region sweep: five-bar candidates judged per second (pairing, key-pose conditions,
   return-stroke inverse kinematics, spline fit, whole-turn closure check).
2. Design NLP: IPOPT with casadi's exact derivatives, against scipy SLSQP on the same
   objective and constraints (casadi-evaluated, derivatives by finite differences),
   from the same start and on the same grid.
3. The whole main job as the CLI runs it (region, NLP, gears, verification, report,
   figures), in a fresh process including start-up; the issue's target is under 10 s.
"""
from __future__ import annotations

import time
from pathlib import Path

import casadi as ca
import numpy as np
from scipy.optimize import minimize

from fresh_process import cli_seconds  # bench/ is the script's own folder
from transplanter.fivebar.nlp import build_nlp, design_nlp
from transplanter.fivebar.problem import load_problem
from transplanter.fivebar.region import solution_region

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "vegetable_planting.toml"


def main():
    problem = load_problem(EXAMPLE)
    start = time.perf_counter()
    region = solution_region(problem)
    sweep = time.perf_counter() - start
    print(f"region sweep: {len(region.candidates)} candidates in {sweep:.3f} s = "
          f"{len(region.candidates) / sweep:,.0f} candidates/s ({len(region.feasible)} feasible)")

    candidate = region.feasible[0]
    start = time.perf_counter()
    solution = design_nlp(problem, candidate)
    ipopt_time = time.perf_counter() - start

    nlp = build_nlp(problem, candidate)
    f = ca.Function("f", [nlp.x], [nlp.objective])
    g = ca.Function("g", [nlp.x], [nlp.constraints])
    equal = nlp.lbg == nlp.ubg
    lower = np.isfinite(nlp.lbg) & ~equal
    upper = np.isfinite(nlp.ubg) & ~equal
    constraints = [
        {"type": "eq", "fun": lambda v: np.asarray(g(v)).ravel()[equal] - nlp.lbg[equal]},
        {"type": "ineq", "fun": lambda v: np.r_[np.asarray(g(v)).ravel()[lower] - nlp.lbg[lower],
                                                 nlp.ubg[upper] - np.asarray(g(v)).ravel()[upper]]},
    ]
    bounds = [(lo if np.isfinite(lo) else None, None) for lo in nlp.lbx]
    start = time.perf_counter()
    baseline = minimize(lambda v: float(f(v)), nlp.x0, method="SLSQP", bounds=bounds, constraints=constraints,
                        options={"maxiter": 500, "ftol": 1e-12})
    scipy_time = time.perf_counter() - start
    violation = np.abs(np.asarray(g(baseline.x)).ravel()[equal]).max()
    print(f"design NLP: IPOPT (exact derivatives) {ipopt_time:.3f} s, objective {solution.objective:.3e}; "
          f"scipy SLSQP (finite differences) {scipy_time:.3f} s, objective {baseline.fun:.3e}, "
          f"equality violation {violation:.1e}, {baseline.message!r}; ratio {scipy_time / ipopt_time:.1f}x")

    print(f"main job (fresh process, figures included): {cli_seconds('fivebar', str(EXAMPLE)):.2f} s (target < 10 s)")

if __name__ == "__main__":
    main()

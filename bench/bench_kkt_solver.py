"""IPOPT with the package's KKT factorisation against IPOPT with its bundled MUMPS, on the main job's own solves.

    python bench/bench_kkt_solver.py [--solves N]

The five-bar example is refined once (candidates in this process, one after another) and every design solve it
makes is recorded: its start, bounds, parameters and, for a warm start, multipliers. Each is then solved again in
this process twice, on the same NLP and with the package's option set: once with the package's factorisation
(``solve/kkt_solver.py``: ``sparse_ldl.c`` through MA27's entry points) and once with MUMPS, without the stall
rule (so both run to IPOPT's own end). It prints each solve's iterations, CPU seconds and status on both sides, and
the totals over the solves where both succeed, with the ratio, and whether the two reach the same objective.
"""
from __future__ import annotations

import argparse
import time
from pathlib import Path

import casadi as ca

from transplanter import fivebar
from transplanter.fivebar.lanes import lanes_here
from transplanter.solve import ipopt
from transplanter.solve.kkt_solver import kkt_solver_options

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "vegetable_planting.toml"


def recorded_solves():
    """(layout, IPOPT's arguments, warm) of every design solve of the example's refinements."""
    calls = []
    solve = ipopt.Solver.solve

    def recording(self, start, bounds=None, parameters=None, iteration_limit=None, failure="", continues=None):
        layout = self.layout
        arguments = self.ipopt_arguments(start, bounds or layout.bounds(), parameters, continues)
        if self.name == "fivebar_design":
            calls.append((layout, arguments, continues is not None))
        return solve(self, start, bounds, parameters, iteration_limit, failure, continues)

    ipopt.Solver.solve = recording
    try:
        with lanes_here():
            fivebar.synthesize(fivebar.load_problem(EXAMPLE))
    finally:
        ipopt.Solver.solve = solve
    return calls


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--solves", type=int, default=None, help="only the first N recorded solves")
    arguments = parser.parse_args()
    package = kkt_solver_options()
    if not package:
        raise SystemExit("the package's factorisation is not compiled (no C compiler at install): nothing to compare")
    options = ipopt.ipopt_options(ipopt.TOLERANCE, ipopt.MAX_ITERATIONS)
    mumps = {key: value for key, value in options.items() if key not in package}
    solvers: dict[tuple, ca.Function] = {}

    def solver(layout, side, warm):
        key = (id(layout), side, warm)
        if key not in solvers:
            chosen = {**(options if side == "package" else mumps), **(ipopt.WARM_START if warm else {})}
            if layout.hessian is not None:
                chosen["hess_lag"] = layout.hessian
            solvers[key] = ca.nlpsol(f"bench_{side}", "ipopt", {"x": layout.x, "p": layout.p, "f": layout.f,
                                                                "g": layout.g}, chosen)
        return solvers[key]

    calls = recorded_solves()[:arguments.solves]
    print(f"{len(calls)} design solves of {EXAMPLE.name}'s refinements; package: {package['ipopt.linear_solver']} "
          f"entry points of {Path(package['ipopt.hsllib']).name}; baseline: MUMPS")
    totals = {"package": [0, 0.0], "mumps": [0, 0.0]}
    largest_gap = 0.0
    for index, (layout, call, warm) in enumerate(calls):
        line, ends, objectives = [], [], []
        for side in ("package", "mumps"):
            function = solver(layout, side, warm)
            start = time.process_time()
            result = function(**call)
            seconds = time.process_time() - start
            stats = function.stats()
            ends.append((stats["return_status"] in ipopt.ACCEPTED, stats["iter_count"], seconds))
            objectives.append(float(result["f"]))
            line.append(f"{side} {stats['iter_count']:4d} its {seconds:6.3f} s {stats['return_status']}")
        print(f"  {index:2d} {'warm' if warm else 'cold'}: " + " | ".join(line))
        if ends[0][0] and ends[1][0]:
            for side, (_, iterations, seconds) in zip(("package", "mumps"), ends, strict=True):
                totals[side][0] += iterations
                totals[side][1] += seconds
            largest_gap = max(largest_gap, abs(objectives[0] - objectives[1]) / max(1.0, abs(objectives[1])))
    (package_its, package_s), (mumps_its, mumps_s) = totals["package"], totals["mumps"]
    print(f"where both succeed: package {package_its} iterations in {package_s:.2f} s CPU "
          f"({1e3 * package_s / max(package_its, 1):.2f} ms each), MUMPS {mumps_its} in {mumps_s:.2f} s "
          f"({1e3 * mumps_s / max(mumps_its, 1):.2f} ms each); ratio {mumps_s / package_s:.2f}x; "
          f"largest objective difference {largest_gap:.1e} (relative)")


if __name__ == "__main__":
    main()

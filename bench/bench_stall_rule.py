"""The stall rule on IPOPT's Hessian regularisation, on the main job's refinements, in one run.

    python bench/bench_stall_rule.py [--rounds N]

Every region candidate of the bundled example refined as the main job's two lanes refine them (lane k:
candidates k, k + 2, ..., each lane on its own design solver, lane 1 on a twin of lane 0's unused one), here
in turn, with the package's stall rule (``design_solver.STALL``) and with the baseline: the same rule
without its part on the regularisation (the rule before it). The two sides alternate within each round.
Printed: each side's CPU per lane (the longer lane sets the refinements' wall time on two cores) and in
all, and their ratios; each candidate whose outcome differs between the sides, with its CPU on each (the
designs must be the same to the bit and the failures stay failures: the rule stops only solves that IPOPT's
own path would not bring to a solution), and the CPU of the candidates that end alike (the timer's noise).
"""
from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ[_variable] = "1"

# Below, each import may load numpy: after the thread counts are set (E402).
import numpy as np  # noqa: E402

from transplanter.errors import SolverError  # noqa: E402
from transplanter.fivebar import design_solver  # noqa: E402
from transplanter.fivebar.design_solver import DesignSolver  # noqa: E402
from transplanter.fivebar.lanes import LANES  # noqa: E402
from transplanter.fivebar.problem import load_problem  # noqa: E402
from transplanter.fivebar.region import solution_region  # noqa: E402
from transplanter.solve import StallRule  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "vegetable_planting.toml"
PACKAGE = design_solver.STALL
BASELINE = StallRule(PACKAGE.violation, PACKAGE.iterations)


def refine_lanes(problem, candidates, rule: StallRule) -> tuple[list[float], list[object]]:
    """CPU seconds and outcome (the design's objective, or the failure's status) of each candidate, with
    ``rule`` as the design solver's stall rule."""
    design_solver.STALL = rule          # read when a DesignSolver builds its IPOPT solver
    try:
        first = DesignSolver(problem)
    finally:
        design_solver.STALL = PACKAGE
    solvers = [first, *(first.twin() for _ in range(1, LANES))]
    seconds, outcomes = [0.0] * len(candidates), [None] * len(candidates)
    for lane, solver in enumerate(solvers):
        for index in range(lane, len(candidates), LANES):
            start = time.process_time()
            try:
                outcomes[index] = solver.refine(candidates[index]).objective
            except SolverError as error:
                outcomes[index] = error.status
            seconds[index] = time.process_time() - start
    return seconds, outcomes


def main(rounds: int) -> None:
    problem = load_problem(EXAMPLE)
    candidates = solution_region(problem).feasible
    print(f"{EXAMPLE.name}: {len(candidates)} region candidates in {LANES} lanes; package rule {PACKAGE}; "
          f"baseline rule {BASELINE}")
    lanes: dict[str, list[list[float]]] = {"baseline": [], "package": []}
    for round_ in range(rounds):
        found, cpu = {}, {}
        for side, rule in (("baseline", BASELINE), ("package", PACKAGE)):
            cpu[side], found[side] = refine_lanes(problem, candidates, rule)
            seconds = [sum(cpu[side][lane::LANES]) for lane in range(LANES)]
            lanes[side].append(seconds)
            print(f"round {round_ + 1} {side:8s}: CPU per lane " + ", ".join(f"{s:.2f}" for s in seconds)
                  + f" s, in all {sum(seconds):.2f} s")
        untouched = [index for index, (before, after) in enumerate(zip(found["baseline"], found["package"],
                                                                           strict=True)) if before == after]
        for index in sorted(set(range(len(candidates))) - set(untouched)):
            before, after = found["baseline"][index], found["package"][index]
            same = isinstance(before, str) and isinstance(after, str)      # a failure on both sides
            print(f"  candidate {index + 1}: {'same outcome' if same else 'OUTCOME DIFFERS'}, CPU "
                  f"{cpu['baseline'][index]:.2f} -> {cpu['package'][index]:.2f} s: {before} -> {after}")
        print(f"  the {len(untouched)} candidates ending alike (the timer's noise): CPU "
              f"{sum(cpu['baseline'][i] for i in untouched):.2f} -> {sum(cpu['package'][i] for i in untouched):.2f} s")
    base, package = np.array(lanes["baseline"]), np.array(lanes["package"])
    longest = package.max(axis=1) / base.max(axis=1)
    total = package.sum(axis=1) / base.sum(axis=1)
    print(f"longer lane's CPU, package / baseline: {', '.join(f'{r:.2f}' for r in longest)} "
          f"(baseline {base.max(axis=1).min():.2f}-{base.max(axis=1).max():.2f} s, package "
          f"{package.max(axis=1).min():.2f}-{package.max(axis=1).max():.2f} s)")
    print(f"both lanes' CPU, package / baseline: {', '.join(f'{r:.2f}' for r in total)} "
          f"(baseline {base.sum(axis=1).min():.2f}-{base.sum(axis=1).max():.2f} s, package "
          f"{package.sum(axis=1).min():.2f}-{package.sum(axis=1).max():.2f} s)")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--rounds", type=int, default=2)
    main(parser.parse_args().rounds)

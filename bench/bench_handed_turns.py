"""The exchange turns a lane hands to its next start, on the bundled example's refinements, in one run.

    python bench/bench_handed_turns.py [--limits 45 48] [--rounds 1]

Every region candidate of the bundled example (its gear pressure limit set to each of ``--limits``, deg)
refined as the main job's two lanes refine them (lane k: candidates k, k + 2, ..., lane 1 on a twin of lane
0's unused solver), here in turn, with the package's choice of the turns handed on (``handed_turns``: those
the design sits on first) and with the baseline: the latest half of the slots' worth added (the rule before
it). Printed per side: IPOPT solves and iterations, the refinements taken from an earlier one's optimum
(``reached_optima``), the CPU per lane and in all, and the ratios; and whether every candidate ends alike
(the designs' objectives to 1e-9; failures stay failures).
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
from transplanter.fivebar.problem import parse_problem  # noqa: E402
from transplanter.fivebar.region import solution_region  # noqa: E402
from transplanter.solve import ipopt  # noqa: E402
from transplanter.toml_fields import read_toml  # noqa: E402

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "vegetable_planting.toml"
PACKAGE = design_solver.handed_turns


def latest_added(solved, blocks, first_slot, added, keep):
    """The baseline: the latest ``keep`` turns added, whatever the design sits on."""
    return added[-keep:]


class Counted:
    """IPOPT solves and iterations of the design solvers while it is entered."""

    def __enter__(self):
        self.solves = self.iterations = 0
        solve = self.solve = ipopt.Solver.solve
        counter = self

        def counted(solver, *args, **kwargs):
            try:
                return solve(solver, *args, **kwargs)
            finally:
                function = solver.function if kwargs.get("continues") is None else solver._warm_function
                counter.solves += 1
                counter.iterations += int(function.stats()["iter_count"])

        ipopt.Solver.solve = counted
        return self

    def __exit__(self, *exc):
        ipopt.Solver.solve = self.solve


def refine_lanes(problem, candidates, choice) -> dict:
    """Each lane's CPU, the outcomes (objective or failure status), the refinements repeated and the IPOPT
    work, with ``choice`` as the design solver's rule for the turns handed on."""
    design_solver.handed_turns = choice
    try:
        first = DesignSolver(problem)
        solvers = [first, *(first.twin() for _ in range(1, LANES))]
        lanes, outcomes = [0.0] * LANES, [None] * len(candidates)
        with Counted() as counted:
            for lane, solver in enumerate(solvers):
                start = time.process_time()
                for index in range(lane, len(candidates), LANES):
                    try:
                        outcomes[index] = solver.refine(candidates[index]).objective
                    except SolverError as error:
                        outcomes[index] = error.status
                lanes[lane] = time.process_time() - start
    finally:
        design_solver.handed_turns = PACKAGE
    return {"lanes": lanes, "outcomes": outcomes, "repeats": sum(solver.repeats for solver in solvers),
            "solves": counted.solves, "iterations": counted.iterations}


def alike(before, after) -> bool:
    if isinstance(before, str) or isinstance(after, str):
        return isinstance(before, str) and isinstance(after, str)
    return abs(before - after) <= 1e-9 * max(1.0, abs(before))


def main(limits: list[float], rounds: int) -> None:
    for limit in limits:
        data = read_toml(EXAMPLE)
        data["gears"]["max_pressure_angle_deg"] = limit
        problem = parse_problem(data, EXAMPLE.name)
        candidates = solution_region(problem).feasible
        print(f"{EXAMPLE.name} with gears.max_pressure_angle_deg = {limit:g}: {len(candidates)} region candidates "
              f"in {LANES} lanes; baseline: the latest turns added")
        for round_ in range(rounds):
            runs = {side: refine_lanes(problem, candidates, choice)
                    for side, choice in (("baseline", latest_added), ("package", PACKAGE))}
            for side, run in runs.items():
                print(f"  round {round_ + 1} {side:8s}: {run['solves']} solves, {run['iterations']} iterations, "
                      f"{run['repeats']} of {len(candidates)} refinements taken from an earlier optimum; CPU per "
                      "lane " + ", ".join(f"{s:.2f}" for s in run["lanes"]) + f" s, in all {sum(run['lanes']):.2f} s")
            base, package = runs["baseline"], runs["package"]
            differ = [index + 1 for index, pair in enumerate(zip(base["outcomes"], package["outcomes"], strict=True))
                      if not alike(*pair)]
            best = [min((o for o in run["outcomes"] if not isinstance(o, str)), default=np.nan)
                    for run in (base, package)]
            print(f"  package / baseline: iterations {package['iterations'] / base['iterations']:.2f}, longer lane's "
                  f"CPU {max(package['lanes']) / max(base['lanes']):.2f}, both lanes' CPU "
                  f"{sum(package['lanes']) / sum(base['lanes']):.2f}; candidates ending otherwise: "
                  f"{differ or 'none'}; best objective {best[0]:.12g} -> {best[1]:.12g}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--limits", type=float, nargs="+", default=[45.0, 48.0],
                        help="gear pressure limits (deg) of the example")
    parser.add_argument("--rounds", type=int, default=1)
    args = parser.parse_args()
    main(args.limits, args.rounds)

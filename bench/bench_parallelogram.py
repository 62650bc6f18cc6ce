"""Time the onion-transplanter design: NSGA-II, vectorised evaluation against a per-individual loop, NLP polish.

    python bench/bench_parallelogram.py

- NSGA-II (pymoo) with population 100 for 100 generations on examples/onion_transplanter.toml
  (target: under 15 s on two cores), the whole population scored per call.
- The same scoring (objectives and constraints of 100 designs) one design per call, as a
  per-individual loop would do it, in the same process; the ratio is printed. Both give the same
  numbers (checked here).
- The same NSGA-II with each population scored in slices on two worker processes (an executor, as a study
  or a cluster would give), against the vectorised scoring in this process: the ratio, and whether the
  Pareto designs are the same (to 1e-9). The workers are started before the clock.
- The NLP polish from the knee (target: under 1 s, including building the NLP).
"""
from __future__ import annotations

import dataclasses
import multiprocessing
import time
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

import numpy as np
from best_time import best_time  # bench/ is the script's own folder

from transplanter.parallelogram import load_problem
from transplanter.parallelogram.evaluation import evaluate
from transplanter.parallelogram.objectives import score
from transplanter.parallelogram.search import SEARCH_SAMPLES, nsga2
from transplanter.parallelogram.synthesis import _polish

ROOT = Path(__file__).resolve().parents[1]



def main():
    print("baseline: the same objectives and constraints scored one design per call, as a per-individual loop "
          "would (NSGA-II and the polish have targets, not baselines)")
    problem = dataclasses.replace(load_problem(ROOT / "examples/onion_transplanter.toml"), population=100,
                                  generations=100)
    import pymoo.algorithms.moo.nsga2  # noqa: F401  (pymoo's first import takes seconds: not the search's time)

    start = time.perf_counter()
    search = nsga2(problem)
    seconds = time.perf_counter() - start
    print(f"NSGA-II: population {problem.population}, {problem.generations} generations, {search.evaluations} "
          f"evaluations in {seconds:.2f} s (target under 15 s); {len(search.designs)} Pareto designs")

    rng = np.random.default_rng(1)
    names = tuple(problem.bounds)
    low = np.array([problem.bounds[n][0] for n in names])
    high = np.array([problem.bounds[n][1] for n in names])
    designs = rng.uniform(low, high, size=(100, len(names)))
    variables = dict(zip(names, designs.T, strict=True))
    whole, scores = best_time(lambda: score(problem, variables, SEARCH_SAMPLES), 5)

    def one_at_a_time():
        return [score(problem, {n: v[k:k + 1] for n, v in variables.items()}, SEARCH_SAMPLES) for k in range(100)]

    loop, singles = best_time(one_at_a_time, 2)
    same = all(np.allclose(s.objectives[0], scores.objectives[k], rtol=1e-12, atol=1e-12)
               for k, s in enumerate(singles))
    print(f"scoring 100 designs: whole population {whole * 1e3:.1f} ms, one design per call {loop * 1e3:.1f} ms: "
          f"ratio {loop / whole:.1f}x (same objectives: {same})")

    with ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as executor:
        list(executor.map(score, [problem] * 2, [variables] * 2, [SEARCH_SAMPLES] * 2))     # workers up and warm
        start = time.perf_counter()
        spread = nsga2(problem, executor=executor)
        spread_seconds = time.perf_counter() - start
    same = spread.designs.shape == search.designs.shape and np.allclose(spread.designs, search.designs, rtol=1e-9,
                                                                         atol=1e-9)
    print(f"NSGA-II scored on two worker processes: {spread_seconds:.2f} s against {seconds:.2f} s vectorised here: "
          f"ratio {spread_seconds / seconds:.2f} (same Pareto designs: {same})")

    knee = {**problem.design, **search.variables(1)}
    evaluation = evaluate(problem, knee)
    polish_time, polished = best_time(lambda: _polish(problem, knee, evaluation), 3)
    print(f"NLP polish from the knee: {polish_time:.3f} s with building the NLP (IPOPT {polished.solve_seconds:.3f} s, "
          f"{polished.iterations} iterations, {polished.status}; target under 1 s); dominates the knee: "
          f"{polished.dominates_start}")


if __name__ == "__main__":
    main()

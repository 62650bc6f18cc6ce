"""NSGA-II over the variables that change an objective (pymoo), the whole population per call.

Settings as in the onion-transplanter paper, section 3.1.2: simulated binary crossover with probability 0.8 and
distribution index 10, polynomial mutation with index 20; population and generations from the
file (the paper: 100 and 200). The first individual is the file's [design] (the start values),
the others uniform in the bounds, all from the file's seed, so a run is reproducible.

The knee of the front: objectives normalised by the front's own ideal and nadir points, the
design nearest the ideal point. The Pareto designs are ranked by that distance (1 = the knee).

Given an executor (a ``concurrent.futures.Executor`` or a ``distributed.Client``), each generation's
population is cut into one slice per worker and the slices scored there, each still in one vectorised call;
the scores are the same row for row, so the search is too.
"""
from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from itertools import repeat
from typing import Any

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.parallelogram.objectives import CONSTRAINTS, OBJECTIVES, score
from transplanter.parallelogram.problem import FILE_NAMES, ParallelogramProblem

SEARCH_SAMPLES = 512        # grid points per turn while searching (the chosen designs are evaluated on 8192)
CROSSOVER_PROBABILITY, CROSSOVER_ETA, MUTATION_ETA = 0.8, 10.0, 20.0


@dataclass(frozen=True)
class SearchResult:
    """The Pareto designs, ranked from the knee.

    Attributes
    ----------
    names : tuple of str
        Searched variables (``VARIABLES`` names; alpha in rad).
    designs : ndarray, shape (n, len(names))
    objectives : ndarray, shape (n, 3)
        f1, f2, f3 (``OBJECTIVES``).
    depth, vx_release, vertical_range : ndarray, shape (n,)
    evaluations : int
    seconds : float
    """

    names: tuple[str, ...]
    designs: np.ndarray
    objectives: np.ndarray
    depth: np.ndarray
    vx_release: np.ndarray
    vertical_range: np.ndarray
    center_distance: np.ndarray
    evaluations: int
    seconds: float

    def variables(self, rank: int) -> dict:
        """Searched variables of the design ranked ``rank`` (1 = the knee), mm and rad."""
        return dict(zip(self.names, (float(v) for v in self.designs[rank - 1]), strict=True))


def knee_order(objectives: np.ndarray) -> np.ndarray:
    """Indices of ``objectives`` by distance to the ideal point after normalising each objective by the
    front's range (ties and flat objectives: range 1)."""
    ideal, nadir = objectives.min(axis=0), objectives.max(axis=0)
    span = np.where(nadir - ideal > 0, nadir - ideal, 1.0)
    return np.argsort(np.linalg.norm((objectives - ideal) / span, axis=1), kind="stable")


def _describe(problem: ParallelogramProblem, names, x: np.ndarray, g: np.ndarray, depth: float) -> str:
    values = ", ".join(f"{FILE_NAMES[n]} = {np.degrees(v) if n == 'alpha' else v:.4g}"
                       for n, v in zip(names, x, strict=True))
    worst = CONSTRAINTS[int(np.argmax(g))]
    return f"the closest design ({values}) has H = {depth:.3f} mm and violates {worst} most"


def scored(problem: ParallelogramProblem, names: tuple[str, ...], samples: int,
           x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """F and G of the designs ``x`` (one row each, columns ``names``): what a worker returns for its slice."""
    scores = score(problem, dict(zip(names, x.T, strict=True)), samples)
    return scores.objectives, scores.constraints


def nsga2(problem: ParallelogramProblem, progress: Callable[[str, int, int], None] | None = None,
          samples: int = SEARCH_SAMPLES, executor: Any = None) -> SearchResult:
    """Run NSGA-II on ``problem``'s bounded variables; the Pareto designs ranked from the knee. With
    ``executor`` (a ``concurrent.futures.Executor`` or a ``distributed.Client``) each population is scored in
    slices on its workers (module docstring).

    Raises
    ------
    InfeasibleError
        When no design of the final population meets the constraints (names the depth band and the
        closest design found).
    """
    from pymoo.algorithms.moo.nsga2 import NSGA2
    from pymoo.core.callback import Callback
    from pymoo.core.problem import Problem
    from pymoo.operators.crossover.sbx import SBX
    from pymoo.operators.mutation.pm import PM
    from pymoo.optimize import minimize

    from transplanter.study.executors import as_executor

    pool, workers = as_executor(executor) if executor is not None else (None, 1)
    names = tuple(problem.bounds)
    low = np.array([problem.bounds[n][0] for n in names])
    high = np.array([problem.bounds[n][1] for n in names])

    class Design(Problem):
        def __init__(self):
            super().__init__(n_var=len(names), n_obj=len(OBJECTIVES), n_ieq_constr=len(CONSTRAINTS), xl=low, xu=high)

        def _evaluate(self, x, out, *args, **kwargs):
            if pool is None:
                out["F"], out["G"] = scored(problem, names, samples, x)
                return
            slices = [rows for rows in np.array_split(x, min(workers, len(x))) if len(rows)]
            parts = list(pool.map(scored, repeat(problem), repeat(names), repeat(samples), slices))
            out["F"], out["G"] = (np.vstack([part[k] for part in parts]) for k in (0, 1))

    class Report(Callback):
        def notify(self, algorithm):
            if progress is not None and (algorithm.n_gen % 10 == 0 or algorithm.n_gen == problem.generations):
                progress("generation", algorithm.n_gen, problem.generations)

    rng = np.random.default_rng(problem.seed)
    start = rng.uniform(low, high, size=(problem.population, len(names)))
    start[0] = np.clip([problem.design[n] for n in names], low, high)
    algorithm = NSGA2(pop_size=problem.population, sampling=start,
                      crossover=SBX(prob=CROSSOVER_PROBABILITY, eta=CROSSOVER_ETA), mutation=PM(eta=MUTATION_ETA),
                      eliminate_duplicates=True)
    began = time.perf_counter()
    result = minimize(Design(), algorithm, ("n_gen", problem.generations), seed=problem.seed, callback=Report(),
                      verbose=False)
    seconds = time.perf_counter() - began
    evaluations = int(result.algorithm.evaluator.n_eval)
    if result.X is None:
        population = result.pop
        x, g = population.get("X"), population.get("G")
        k = int(np.argmin(np.maximum(g, 0).sum(axis=1)))
        depth = score(problem, dict(zip(names, x[k:k + 1].T, strict=True)), samples).measures.depth[0]
        band = list(problem.depth_band)
        raise InfeasibleError(
            f"{problem.source}: objectives.depth_band_mm = {band}: no design within search.bounds meets it and the "
            f"gear constraints after {evaluations} evaluations; {_describe(problem, names, x[k], g[k], depth)}; "
            "widen the band or the bounds")
    x = np.atleast_2d(result.X)
    scores = score(problem, dict(zip(names, x.T, strict=True)), samples)
    order = knee_order(scores.objectives)
    m = scores.measures
    return SearchResult(names, x[order], scores.objectives[order], m.depth[order], m.vx_release[order],
                        m.vertical_range[order], scores.center_distance[order], evaluations, seconds)

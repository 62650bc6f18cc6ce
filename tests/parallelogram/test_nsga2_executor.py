"""NSGA-II with its populations scored on an executor's workers: the same search as the vectorised one in
this process, to 1e-9."""
import dataclasses
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from transplanter.errors import ProblemError
from transplanter.parallelogram import load_problem
from transplanter.parallelogram.search import nsga2

PROBLEM = Path(__file__).resolve().parents[2] / "examples/onion_transplanter.toml"


@pytest.fixture(scope="module")
def problem():
    return dataclasses.replace(load_problem(PROBLEM), population=13, generations=4)   # 13: slices of unequal size


@pytest.fixture(scope="module")
def in_process(problem):
    return nsga2(problem)


def same_search(first, second) -> bool:
    return (first.evaluations == second.evaluations and first.designs.shape == second.designs.shape
            and np.allclose(first.designs, second.designs, rtol=1e-9, atol=1e-9)
            and np.allclose(first.objectives, second.objectives, rtol=1e-9, atol=1e-9))


@pytest.mark.parametrize("workers", [2, 5])
def test_threads_give_the_vectorised_search(problem, in_process, workers):
    with ThreadPoolExecutor(workers) as executor:
        assert same_search(nsga2(problem, executor=executor), in_process)


def test_worker_processes_give_the_vectorised_search(problem, in_process):
    """The slices and the problem cross to the workers by pickling."""
    with ProcessPoolExecutor(2) as executor:
        assert same_search(nsga2(problem, executor=executor), in_process)


def test_something_that_is_no_executor_is_refused_by_name(problem):
    with pytest.raises(ProblemError, match="executor = list: expected a concurrent.futures.Executor"):
        nsga2(problem, executor=[])


def test_synthesis_scores_its_search_on_the_executor_it_is_given(problem):
    """``synthesize(executor=)`` hands the executor to its search: the same design as in this process."""
    from transplanter.parallelogram import synthesize

    class CountingPool(ThreadPoolExecutor):
        submitted = 0

        def submit(self, *args, **kwargs):
            CountingPool.submitted += 1
            return super().submit(*args, **kwargs)

    alone = synthesize(problem, polish_nlp=False, tolerance=False)
    with CountingPool(2) as executor:
        shared = synthesize(problem, polish_nlp=False, tolerance=False, executor=executor)
    assert CountingPool.submitted >= 2 * problem.generations     # two slices for each generation's population
    assert same_search(shared.search, alone.search)
    assert shared.chosen == pytest.approx(alone.chosen, rel=1e-9, abs=1e-9)


def test_synthesis_refuses_something_that_is_no_executor_by_name(problem):
    from transplanter.parallelogram import synthesize

    with pytest.raises(ProblemError, match="executor = dict: expected a concurrent.futures.Executor"):
        synthesize(problem, tolerance=False, executor={})

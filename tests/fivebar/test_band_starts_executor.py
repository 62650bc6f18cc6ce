"""The band starts with the drawn pose sets' regions built on an executor's workers: the same trials and the same
starts as built here one after the other (to 1e-9)."""
import dataclasses
from concurrent.futures import ProcessPoolExecutor, ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from transplanter.fivebar import parse_problem
from transplanter.fivebar.band_search import band_starts
from transplanter.toml_fields import read_toml

BANDS = Path(__file__).resolve().parents[2] / "examples/vegetable_planting_bands.toml"


def bands_problem(**region):
    """The bands example with a coarse region (300 samples: its 13 first drawn sets hold no five-bar, the 14th
    does; checked below, not assumed)."""
    data = read_toml(BANDS)
    data["region"].update(samples=300, **region)
    return parse_problem(data, "bands.toml")


def dimensions(mech) -> np.ndarray:
    return np.hstack([np.ravel(value) for value in dataclasses.astuple(mech)])


def same_starts(first, second) -> bool:
    close = lambda a, b: np.allclose(a, b, rtol=1e-9, atol=1e-9)     # noqa: E731
    trials = len(first.trials) == len(second.trials) and all(
        close(a.poses, b.poses) and close(a.carrier_turns, b.carrier_turns) and a.feasible == b.feasible
        and a.binding == b.binding for a, b in zip(first.trials, second.trials, strict=True))
    ones, others = first.candidates, second.candidates
    return trials and close(first.problem.poses, second.problem.poses) and len(ones) == len(others) and all(
        close(dimensions(a.mech), dimensions(b.mech)) and close(a.poses, b.poses)
        and close(a.carrier_turns, b.carrier_turns) for a, b in zip(ones, others, strict=True))


@pytest.fixture(scope="module")
def here():
    return band_starts(bands_problem())


def test_the_coarse_bands_example_tries_several_sets_before_one_gives_a_five_bar(here):
    assert len(here.trials) > 4 and here.trials[-1].feasible and not any(t.feasible for t in here.trials[:-1])
    assert all(c.poses is not None for c in here.candidates)


@pytest.mark.parametrize("workers", [3, 4])
def test_threads_give_the_same_starts(here, workers):
    """Waves of 3 and 4 sets: the set that gives a five-bar falls inside a wave, others after it are dropped."""
    with ThreadPoolExecutor(workers) as executor:
        assert same_starts(band_starts(bands_problem(), executor), here)


def test_worker_processes_give_the_same_starts(here):
    with ProcessPoolExecutor(2) as executor:
        assert same_starts(band_starts(bands_problem(), executor), here)


def test_when_no_set_gives_a_five_bar_every_trial_and_the_last_region_are_the_same():
    """|EP| held to 55-56 mm: no region of the bands holds a five-bar."""
    problem_data = read_toml(BANDS)
    problem_data["region"].update(samples=300, band_samples=5)
    problem_data["ranges"].update(ep=[55.0, 56.0])
    problem = parse_problem(problem_data, "narrow.toml")
    alone = band_starts(problem)
    with ThreadPoolExecutor(2) as executor:
        spread = band_starts(problem, executor)
    assert len(alone.trials) == 6 and not alone.candidates and same_starts(spread, alone)
    assert len(spread.region.candidates) == len(alone.region.candidates)

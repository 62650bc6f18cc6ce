"""Starts for the design NLP when the key poses are bands: the solution region needs exact poses, so it is
built at the bands' centres; where that holds no feasible five-bar, pose sets are drawn inside the bands
(seeded, so a run repeats; each meets the relative requirements) and their regions built, until one holds
feasible five-bars or ``[region] band_samples`` sets have been tried. Each set tried is kept with why its
region was empty, named by the condition that emptied it.

Given an executor (a ``concurrent.futures.Executor`` or a ``distributed.Client``), the drawn sets' regions are
built on its workers, as many at once as it has workers; the sets are drawn before any is tried and the
first one in drawing order whose region holds a five-bar is taken, so the starts and the trials are the ones
found without it (the regions built past that set are dropped)."""
from __future__ import annotations

import dataclasses
from collections import Counter
from collections.abc import Iterator
from dataclasses import dataclass
from itertools import repeat
from typing import Any

import numpy as np

from transplanter.fivebar.candidate import Candidate
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import Region, solution_region

#: Seed of the pose sets drawn inside the bands.
SEED = 20261127


@dataclass(frozen=True)
class PoseSetTrial:
    """A pose set tried (mm, rad): how many feasible five-bars its region held and, when none, the condition
    that emptied it."""

    poses: np.ndarray
    carrier_turns: np.ndarray
    feasible: int
    binding: str


@dataclass(frozen=True)
class BandStarts:
    """The region that gave the starts, its problem (the pose set it was built for) and every set tried."""

    region: Region
    problem: FiveBarProblem
    trials: tuple[PoseSetTrial, ...]

    @property
    def candidates(self) -> list[Candidate]:
        """The region's feasible five-bars, each carrying its pose set when it is not the problem's own."""
        return self.region.feasible

    def most_binding(self) -> str:
        """The condition that emptied the most regions, with how many of the sets tried it emptied."""
        counts = Counter(trial.binding for trial in self.trials if not trial.feasible)
        name, count = counts.most_common(1)[0]
        return f"{name} (emptied {count} of the {len(self.trials)} pose sets tried)"


def empty_region_cause(region: Region) -> str:
    """The condition that left a region without a feasible five-bar, by name: the one that removed the last
    dyads of a chain family, or the one that removed the most pairs."""
    for name, family in (("2R chain B-E", region.receiving), ("3R chain O-A-F", region.carrier)):
        if not family.kept.any():
            if not len(family.fixed):
                return f"{name}: no dyad traced within region.radius_mm"
            return f"{name}: {[key for key, count in family.reasons.items() if count][-1]}"
    return max(region.pair_defects.items(), key=lambda item: item[1])[0]


def band_starts(problem: FiveBarProblem, executor: Any = None) -> BandStarts:
    """The region of the key poses (their bands' centres), or of the first pose set drawn inside the bands
    whose region holds a feasible five-bar (``problem.band_samples`` sets at most); the drawn sets' regions on
    ``executor``'s workers when one is given (module docstring). Without bands, or when no set gives one, the
    last region built is returned with every trial (its ``feasible`` is then empty)."""
    region = solution_region(problem)
    trials = [_trial(problem.poses, problem.carrier_turns, region)]
    bands = problem.pose_bands
    if region.feasible or bands is None:
        return BandStarts(region, problem, tuple(trials))
    drawn_sets = _drawn_sets(problem)
    for drawn, (trial, looked) in zip(drawn_sets, _looks(problem, drawn_sets, executor), strict=False):
        trials.append(trial)
        if trial.feasible:
            assert looked is not None, "a look keeps the region that holds a five-bar"
            carried = [dataclasses.replace(c, poses=drawn[:, :3], carrier_turns=drawn[:, 3]) for c in looked.feasible]
            region = dataclasses.replace(looked, candidates=carried + looked.candidates[len(carried):])
            return BandStarts(region, problem.with_poses(drawn[:, :3], drawn[:, 3]), tuple(trials))
        region = looked if looked is not None else region
    return BandStarts(region, problem, tuple(trials))


def _drawn_sets(problem: FiveBarProblem) -> list[np.ndarray]:
    """The pose sets drawn inside the bands (seeded), ``problem.band_samples`` at most: fewer when the bands
    give no more that meet the relative requirements."""
    assert problem.pose_bands is not None
    rng = np.random.default_rng(SEED)
    drawn_sets = []
    for _ in range(problem.band_samples):
        drawn = problem.pose_bands.sample(rng, problem.requirements, problem.stroke_direction)
        if drawn is None:
            break
        drawn_sets.append(drawn)
    return drawn_sets


def _looks(problem: FiveBarProblem, drawn_sets: list[np.ndarray], executor: Any) -> Iterator[
        tuple[PoseSetTrial, Region | None]]:
    """``look`` at each drawn set in order: here one at a time, or on ``executor`` as many at once as it has
    workers; the caller stops asking when it has what it needs."""
    from transplanter.study.executors import as_executor

    pool, width = as_executor(executor) if executor is not None else (None, 1)
    last = len(drawn_sets) - 1
    for first in range(0, len(drawn_sets), width):
        wave = range(first, min(first + width, len(drawn_sets)))
        yield from (pool.map if pool else map)(look, repeat(problem), [drawn_sets[k] for k in wave],
                                               [k == last for k in wave])


def look(problem: FiveBarProblem, drawn: np.ndarray, keep: bool) -> tuple[PoseSetTrial, Region | None]:
    """The trial of the pose set ``drawn`` (its quick region: the next set is cheaper than a hold), and the region
    itself when it holds a five-bar or ``keep`` (the last set) asks for it: only those cross back from a
    worker."""
    region = solution_region(problem.with_poses(drawn[:, :3], drawn[:, 3]), hold=False)
    return _trial(drawn[:, :3], drawn[:, 3], region), region if region.feasible or keep else None


def _trial(poses: np.ndarray, turns: np.ndarray, region: Region) -> PoseSetTrial:
    count = len(region.feasible)
    return PoseSetTrial(np.array(poses, float), np.array(turns, float), count,
                        "" if count else empty_region_cause(region))

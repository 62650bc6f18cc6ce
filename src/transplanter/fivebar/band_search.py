"""Starts for the design NLP when the key poses are bands: the solution region needs exact poses, so it is
built at the bands' centres; where that holds no feasible five-bar, pose sets are drawn inside the bands
(seeded, so a run repeats; each meets the relative requirements) and their regions built, until one holds
feasible five-bars or ``[region] band_samples`` sets have been tried. Each set tried is kept with why its
region was empty, named by the condition that emptied it."""
from __future__ import annotations

import dataclasses
from collections import Counter
from dataclasses import dataclass

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


def band_starts(problem: FiveBarProblem) -> BandStarts:
    """The region of the key poses (their bands' centres), or of the first pose set drawn inside the bands
    whose region holds a feasible five-bar (``problem.band_samples`` sets at most). Without bands, or when no
    set gives one, the last region built is returned with every trial (its ``feasible`` is then empty)."""
    region = solution_region(problem)
    trials = [_trial(problem.poses, problem.carrier_turns, region)]
    bands = problem.pose_bands
    if region.feasible or bands is None:
        return BandStarts(region, problem, tuple(trials))
    rng = np.random.default_rng(SEED)
    for _ in range(problem.band_samples):
        drawn = bands.sample(rng, problem.requirements, problem.stroke_direction)
        if drawn is None:
            break
        trial_problem = problem.with_poses(drawn[:, :3], drawn[:, 3])
        region = solution_region(trial_problem, hold=False)     # a quick look: the next set is cheaper than a hold
        trials.append(_trial(drawn[:, :3], drawn[:, 3], region))
        if region.feasible:
            carried = [dataclasses.replace(c, poses=drawn[:, :3], carrier_turns=drawn[:, 3]) for c in region.feasible]
            region = dataclasses.replace(region, candidates=carried + region.candidates[len(carried):])
            return BandStarts(region, trial_problem, tuple(trials))
    return BandStarts(region, problem, tuple(trials))


def _trial(poses: np.ndarray, turns: np.ndarray, region: Region) -> PoseSetTrial:
    count = len(region.feasible)
    return PoseSetTrial(np.array(poses, float), np.array(turns, float), count,
                        "" if count else empty_region_cause(region))

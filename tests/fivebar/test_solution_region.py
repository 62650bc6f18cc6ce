"""The five-bar solution region judged with array operations (against the one-at-a-time reference), its sampling
and its limits."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest

from transplanter.errors import ProblemError
from transplanter.fivebar import return_stroke
from transplanter.fivebar.candidate import evaluate_candidate, judge_candidates
from transplanter.fivebar.linkage import FiveBar, from_hinges
from transplanter.fivebar.problem import parse_problem
from transplanter.fivebar.reference_region import exhaustive_return_strokes, reference_candidate, reference_region
from transplanter.fivebar.region import PAIR_LIMIT, chain_families, solution_region
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.fivebar.return_stroke import SEQUENCE_LIMIT, stroke_sequences
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[2]
EXAMPLE = ROOT / "examples/vegetable_planting.toml"


@pytest.fixture(scope="module")
def problem(example_problem):
    return example_problem


def _same_candidate(old, new):
    assert old.defects == new.defects
    for name in ("carrier_length", "carrier_angle", "rod_length", "hinge_b", "receiving_length", "e_local",
                 "f_local", "branch"):
        assert np.array_equal(getattr(old.mech, name), getattr(new.mech, name))
    assert np.array_equal(old.key_relative_angles, new.key_relative_angles)
    assert (old.stroke is None) == (new.stroke is None) and (old.relative_angle is None) == (new.relative_angle is None)
    if old.stroke is not None:
        for field in ("carrier_turns", "relative_angles", "directions"):
            assert np.array_equal(getattr(old.stroke, field), getattr(new.stroke, field))
        assert old.relative_angle.rho1 == new.relative_angle.rho1
        assert np.array_equal(old.relative_angle.coefficients, new.relative_angle.coefficients)
    assert np.array_equal([old.min_margin, *old.ratio_range], [new.min_margin, *new.ratio_range], equal_nan=True)


def test_region_equals_the_one_at_a_time_reference_for_every_candidate(problem):
    """Every one of the example's 1560 pairs: the same verdict, defect texts, numbers and rank as
    judging it alone with an exhaustive return-stroke search (``fivebar.reference_region``)."""
    reference = reference_region(problem)
    reference.sort(key=lambda c: (not c.feasible, -np.nan_to_num(c.min_margin, nan=-np.inf)))
    region = solution_region(problem)
    assert len(region.candidates) == len(reference) == 1560
    assert sum(c.stroke is not None for c in reference) > 100 and len(region.feasible) == 18
    for old, new in zip(reference, region.candidates, strict=True):
        _same_candidate(old, new)


def test_batch_with_ranges_equals_one_at_a_time(problem, rng):
    """check_ranges on: a seeded random set of pairs of all traced dyads (most outside the ranges)."""
    receiving, carrier = chain_families(problem)
    i = rng.integers(len(receiving.fixed), size=(300, 1))
    j = rng.integers(len(carrier.fixed), size=(300, 1))
    batch = from_hinges(problem.poses[0], receiving.fixed[i], receiving.moving[i], carrier.fixed[j],
                        carrier.moving[j])
    judged = judge_candidates(problem, batch)
    assert any(d.startswith("ranges.") for c in judged for d in c.defects)
    assert any(d.startswith("order") for c in judged for d in c.defects)
    for k, new in enumerate(judged):
        _same_candidate(reference_candidate(problem, batch[k, 0]), new)
        _same_candidate(new, evaluate_candidate(problem, batch[k, 0]))


@pytest.mark.parametrize("limit", [SEQUENCE_LIMIT, 1])
def test_return_strokes_are_the_cheapest_of_the_exhaustive_search(rng, monkeypatch, limit):
    """Seeded five-bars near a known one, with 7 return points taken off its path: the strokes kept are the
    ``limit`` cheapest consistent ones of all 4^7 option sequences, cheapest first (none: none); some mechanisms
    pass the points on more sequences than a limit of 1 keeps."""
    monkeypatch.setattr(return_stroke, "SEQUENCE_LIMIT", limit)
    known = FiveBar(48.0, -0.5, 246.0, np.array([-78.6, -30.1]), 186.0, np.array([99.4, -11.3]),
                    np.array([35.0, -33.1]), -1.0)
    relative = RelativeAngle(-1.26, np.radians([0, 3, -4, 2, 0, 1, -2, 3, 0, -1, 2, 0]))
    turns = np.radians([130.0, 160.0, 190.0, 230.0, 270.0, 300.0, 330.0])
    points = known.forward(turns, relative.evaluate(turns))["p"]
    key = np.radians(90.0)
    last = known.forward(np.array([key]), relative.evaluate(np.array([key])))
    mechs = [dataclasses.replace(known, carrier_length=known.carrier_length * s1, rod_length=known.rod_length * s2,
                                 receiving_length=known.receiving_length * s3)
             for s1, s2, s3 in 1 + 0.03 * rng.normal(size=(40, 3))]
    batch = FiveBar(*(np.stack([np.asarray(v, float) for v in values])[:, None]
                      for values in zip(*(vars(m).values() for m in mechs), strict=True)))
    rho1, last_rho = np.full(40, relative.rho1), np.full(40, float(relative.evaluate(key)))
    direction = float(last["direction"][0])
    sequences = stroke_sequences(batch, points, key, rho1, last_rho, direction)
    counts = []
    for k, mech in enumerate(mechs):
        exhaustive = exhaustive_return_strokes(mech, points, key, rho1[k], last_rho[k], direction)
        rows = np.flatnonzero(sequences.owner == k)
        assert len(rows) == min(len(exhaustive), limit)
        for row, stroke in zip(rows, exhaustive, strict=False):
            assert np.array_equal(sequences.stroke.carrier_turns[row], stroke.carrier_turns)
            assert np.array_equal(sequences.stroke.directions[row], stroke.directions)
        counts.append(len(exhaustive))
    assert min(counts) == 0 and max(counts) > 1


def test_default_sampling_starts_from_the_dyad_pair_of_2000_samples(problem, example_result):
    """The default [region] samples offer the NLP a start from the same dyad pair as 2000 samples, the
    example's own setting: the sampled hinges B and A within 1 mm. The designs are not compared here: the
    max-min NLP has several local optima and which one a start reaches depends on IPOPT's path (before the
    return points' other passes were tried, one machine's default starts reached an angle EBF of 6.74 deg
    where 2000 samples gave 6.36)."""
    data = read_toml(EXAMPLE)
    del data["region"]["samples"]
    default = parse_problem(data, "default.toml")
    assert default.samples < problem.samples == 2000
    region = solution_region(default)
    assert len(region.feasible) >= 3 and len(example_result.region.feasible) >= 3
    fine = example_result.start
    hinges = np.array([np.r_[start.mech.hinge_b, start.mech.carrier_point(0.0)] for start in region.feasible])
    nearest = np.abs(hinges - np.r_[fine.mech.hinge_b, fine.mech.carrier_point(0.0)]).max(axis=1).min()
    assert nearest < 1.0


def test_too_many_pairs_without_ranges_is_one_problem_error():
    """Without [ranges], 2000 samples pair every traced dyad: millions of five-bars, refused before judging."""
    data = read_toml(EXAMPLE)
    del data["ranges"]
    problem = parse_problem(data, "f.toml")
    with pytest.raises(ProblemError,
                       match=r"f\.toml: region\.samples = 2000: expected at most about (\d+) here") as error:
        solution_region(problem)
    message = str(error.value)
    fitting = int(message.split("at most about ")[1].split(" ")[0])
    assert "without [ranges]" in message and f"{PAIR_LIMIT}" in message
    receiving, carrier = chain_families(dataclasses.replace(problem, samples=fitting))
    assert receiving.kept.sum() * carrier.kept.sum() <= PAIR_LIMIT * 1.05     # the advice is (about) right


def test_samples_above_the_accepted_maximum_are_refused():
    data = read_toml(EXAMPLE)
    data["region"]["samples"] = 200_000
    with pytest.raises(ProblemError, match=r"region\.samples = 200000: expected a whole number from 64 to"):
        parse_problem(data, "f.toml")

"""Speed of the five-bar solution region: array judgement against the per-candidate loop.

    python bench/bench_region.py

1. The region at several ``[region] samples``: five-bars judged, seconds, and the exponent
   of time against the number of five-bars (fitted in log-log), for the package and for the
   former loop that judged one five-bar at a time (``fivebar.reference_region``).
2. Whether the sampling changes the answer: the start candidate and the refined design at
   the default sampling against 2000 samples.
3. The region with ``[ranges]`` left out (every dyad within ``region.radius_mm`` is kept).

Both run in this one process, so their ratio holds on a loaded machine; absolute times do not.
"""
from __future__ import annotations

import dataclasses
import time
from pathlib import Path

import numpy as np

from transplanter.errors import ProblemError
from transplanter.fivebar.problem import FiveBarProblem, load_problem, parse_problem
from transplanter.fivebar.reference_region import reference_region
from transplanter.fivebar.region import solution_region
from transplanter.fivebar.synthesis import synthesize
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "vegetable_planting.toml"
SAMPLES = (250, 500, 1000, 2000, 4000, 8000)


def _seconds(function, *arguments):
    start = time.perf_counter()
    value = function(*arguments)
    return time.perf_counter() - start, value


def _exponent(counts, seconds) -> float:
    return float(np.polyfit(np.log(counts), np.log(seconds), 1)[0])


def scaling(problem: FiveBarProblem, baseline_up_to: int = 4000):
    rows = []
    for samples in SAMPLES:
        sampled = dataclasses.replace(problem, samples=samples)
        package, region = _seconds(solution_region, sampled)
        former = _seconds(reference_region, sampled)[0] if samples <= baseline_up_to else float("nan")
        rows.append((samples, len(region.candidates), len(region.feasible), package, former))
        print(f"samples {samples:5d}: {len(region.candidates):7d} five-bars, {len(region.feasible):4d} feasible, "
              f"region {package:7.3f} s, former loop {former:7.3f} s")
    counts, package, former = (np.array([row[k] for row in rows], float) for k in (1, 3, 4))
    big = counts >= 400            # below that, the dyad tracing (linear in samples) dominates
    both = big & np.isfinite(former)
    print(f"exponent of region time against five-bars (>= 400 of them): "
          f"package {_exponent(counts[big], package[big]):.2f}, "
          f"former loop {_exponent(counts[both], former[both]):.2f}; "
          f"at {int(counts[both][-1])} five-bars the "
          f"package takes {package[both][-1] / former[both][-1]:.3f} of the former loop's time")


def _design_numbers(result) -> np.ndarray:
    mech = result.design.mech
    return np.r_[mech.carrier_length, mech.carrier_angle, mech.rod_length, mech.hinge_b, mech.receiving_length,
                 mech.e_local, mech.f_local, result.design.relative_angle.coefficients]


def sampling_answer(problem: FiveBarProblem, default: int):
    """The refined design at the default sampling against 2000 samples."""
    results = {samples: synthesize(dataclasses.replace(problem, samples=samples)) for samples in (default, 2000)}
    starts = [np.r_[r.start.mech.hinge_b, r.start.mech.carrier_point(0.0)] for r in results.values()]
    change = np.abs(_design_numbers(results[default]) - _design_numbers(results[2000])).max()
    print(f"default {default} samples against 2000: start hinges B, A differ by "
          f"{np.abs(starts[0] - starts[1]).max():.2f} mm; refined design numbers differ by at most {change:.2e}")


def without_ranges(problem: FiveBarProblem):
    data = read_toml(EXAMPLE)
    del data["ranges"]
    for samples in (500, problem.samples):
        data["region"]["samples"] = samples
        try:
            seconds, region = _seconds(solution_region, parse_problem(data, "no-ranges"))
            print(f"no [ranges], {samples} samples: {len(region.candidates)} five-bars, {len(region.feasible)} "
                  f"feasible, region {seconds:.2f} s")
        except ProblemError as error:
            print(f"no [ranges], {samples} samples: refused: {error}")


def main():
    print("baseline: the former loop that judged one five-bar at a time (fivebar.reference_region), same samples")
    problem = load_problem(EXAMPLE)
    default = parse_problem({**read_toml(EXAMPLE), "region": {}}, "default").samples
    scaling(problem)
    sampling_answer(problem, default)
    without_ranges(dataclasses.replace(problem, samples=default))


if __name__ == "__main__":
    main()

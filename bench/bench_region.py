"""Speed of the five-bar solution region (issue 17): array judgement against the per-candidate loop.

    python bench/bench_region.py

1. The region at several ``[region] samples``: five-bars judged, seconds, and the exponent
   of time against the number of five-bars (fitted in log-log), for the package and for the
   former loop that judged one five-bar at a time (``baseline_region``, kept here only).
2. Whether the sampling changes the answer: the start candidate and the refined design at
   the default sampling against 2000 samples.
3. The region with ``[ranges]`` left out (every dyad within ``region.radius_mm`` is kept).

Both run in this one process, so their ratio holds on a loaded machine; absolute times do not.
"""
from __future__ import annotations

import dataclasses
import itertools
import time
from pathlib import Path

import numpy as np

from transplanter.errors import ProblemError
from transplanter.fivebar.candidate import (
    BRANCH,
    CRANK,
    RETURN,
    Candidate,
    closure_defect,
    crank_exists,
    monotonic_defect,
    order_defect,
    range_defect,
    range_values,
    ratio_defect,
    whole_turn,
)
from transplanter.fivebar.linkage import FiveBar, assembly_branch, from_hinges
from transplanter.fivebar.problem import FiveBarProblem, load_problem, parse_problem
from transplanter.fivebar.region import chain_families, solution_region
from transplanter.fivebar.relative_angle import fit_relative_angle, ratio_range
from transplanter.fivebar.return_stroke import SEQUENCE_LIMIT, ReturnStroke, _options
from transplanter.fivebar.synthesis import synthesize
from transplanter.geometry.planar import TWO_PI
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "vegetable_planting.toml"
SAMPLES = (250, 500, 1000, 2000, 4000, 8000)


def baseline_return_strokes(mech: FiveBar, points, last_turn, rho1, last_rho, last_direction):
    """The former search: every one of the 4^m option sequences of one mechanism; the consistent ones, cheapest
    first (a stable sort: ties in the order of ``itertools.product``)."""
    c, rho, direction, valid = (values[0] for values in _options(mech.as_batch(), points))
    rho = rho1 + np.mod(rho - rho1, TWO_PI)
    m = len(points)
    combos = np.array(list(itertools.product(range(4), repeat=m)))
    pick = (np.arange(m), combos)
    cs = np.c_[np.full(len(combos), last_turn), c[pick], np.full(len(combos), TWO_PI)]
    rs = np.c_[np.full(len(combos), last_rho), rho[pick], np.full(len(combos), rho1 + TWO_PI)]
    ok = np.all(np.isfinite(valid[pick]) & np.isfinite(cs[:, 1:-1]), axis=1)
    ok &= np.all(np.diff(cs, axis=1) > 0, axis=1) & np.all(np.diff(rs, axis=1) > 0, axis=1)
    turn = np.diff(np.c_[np.full(len(combos), last_direction), direction[pick]], axis=1)
    cost = np.sum(np.angle(np.exp(1j * turn))**2, axis=1)
    ranked = np.flatnonzero(ok)[np.argsort(cost[ok], kind="stable")]
    return [ReturnStroke(c[(np.arange(m), combos[k])], rho[(np.arange(m), combos[k])],
                         direction[(np.arange(m), combos[k])]) for k in ranked]


def baseline_candidate(problem: FiveBarProblem, mech: FiveBar, check_ranges: bool = True) -> Candidate:
    """The former ``evaluate_candidate``: one five-bar judged with its own calls, condition after condition,
    its return strokes one after another."""
    turns = problem.carrier_turns
    rho = mech.relative_angle_at(problem.poses, turns)
    rho = rho[0] + np.mod(rho - rho[0], TWO_PI)
    values = range_values(problem, mech)
    defects = [range_defect(key, values[key], bounds) for key, bounds in problem.ranges.items()
               if not bounds[0] <= values[key] <= bounds[1]] if check_ranges else []
    if np.any(np.diff(rho) <= 0):
        defects.append(order_defect(rho))
    e, f = mech.plate_points(problem.poses)
    if np.any(assembly_branch(mech.hinge_b, e, f) != mech.branch):
        defects.append(BRANCH)
    if not crank_exists(mech):
        defects.append(CRANK)
    if defects:
        return Candidate(mech, rho, defects)
    strokes = baseline_return_strokes(mech, problem.return_points, turns[-1], rho[0], rho[-1], problem.poses[-1, 2])
    if not strokes:
        return Candidate(mech, rho, [RETURN])
    judged = []
    for stroke in strokes[:SEQUENCE_LIMIT]:
        relative = fit_relative_angle(np.r_[turns, stroke.carrier_turns], np.r_[rho, stroke.relative_angles],
                                      problem.spline_count)
        margin, slope = whole_turn(mech, relative)
        ratio = ratio_range(slope)
        defects = []
        if slope.min() <= 0:
            defects.append(monotonic_defect(slope))
        elif ratio[0] < problem.ratio_bounds[0] or ratio[1] > problem.ratio_bounds[1]:
            defects.append(ratio_defect(*ratio, problem.ratio_bounds))
        if not margin >= problem.min_closure_margin:
            defects.append(closure_defect(margin, problem.min_closure_margin))
        judged.append(Candidate(mech, rho, defects, stroke, relative, margin, ratio))
        if not defects:
            break
    return judged[-1] if judged[-1].feasible else judged[0]


def baseline_region(problem: FiveBarProblem) -> list[Candidate]:
    """The former pairing loop: every pair of kept dyads built and judged one at a time, in pair order."""
    receiving, carrier = chain_families(problem)
    return [baseline_candidate(problem, from_hinges(problem.poses[0], receiving.fixed[i], receiving.moving[i],
                                                    carrier.fixed[j], carrier.moving[j]), check_ranges=False)
            for i in np.flatnonzero(receiving.kept) for j in np.flatnonzero(carrier.kept)]


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
        former = _seconds(baseline_region, sampled)[0] if samples <= baseline_up_to else float("nan")
        rows.append((samples, len(region.candidates), len(region.feasible), package, former))
        print(f"samples {samples:5d}: {len(region.candidates):7d} five-bars, {len(region.feasible):4d} feasible, "
              f"region {package:7.3f} s, former loop {former:7.3f} s")
    counts, package, former = (np.array([row[k] for row in rows], float) for k in (1, 3, 4))
    big = counts >= 400            # below that, the dyad tracing (linear in samples) dominates
    both = big & np.isfinite(former)
    print(f"exponent of region time against five-bars (>= 400 of them): package {_exponent(counts[big], package[big]):.2f}"
          f", former loop {_exponent(counts[both], former[both]):.2f}; at {int(counts[both][-1])} five-bars the "
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
    problem = load_problem(EXAMPLE)
    default = parse_problem({**read_toml(EXAMPLE), "region": {}}, "default").samples
    scaling(problem)
    sampling_answer(problem, default)
    without_ranges(dataclasses.replace(problem, samples=default))


if __name__ == "__main__":
    main()

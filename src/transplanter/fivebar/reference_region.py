"""The five-bar region judged the plain way: one five-bar at a time, condition after condition, each with
its own calls, and the return strokes by trying every one of the 4^m option sequences.

It is the independent reference that the array judgement (``candidate.judge_candidates`` with
``return_stroke.solve_return_strokes``) must equal exactly (the tests), and the baseline that judgement is
timed against (``bench/bench_region.py``); the package itself never calls it.
"""
from __future__ import annotations

import itertools

import numpy as np

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
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import chain_families
from transplanter.fivebar.relative_angle import fit_relative_angle, ratio_range
from transplanter.fivebar.return_stroke import SEQUENCE_LIMIT, ReturnStroke, _options

TWO_PI = 2 * np.pi


def exhaustive_return_strokes(mech: FiveBar, points, last_turn, rho1, last_rho, last_direction) -> list[ReturnStroke]:
    """Every one of the 4^m option sequences of one mechanism tried: the consistent ones, cheapest first (a stable
    sort: ties in the order of ``itertools.product``)."""
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


def reference_candidate(problem: FiveBarProblem, mech: FiveBar, check_ranges: bool = True) -> Candidate:
    """One five-bar judged with its own calls, condition after condition, its return strokes tried one after
    another, cheapest first (what ``evaluate_candidate`` without ``hold`` must equal)."""
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
    strokes = exhaustive_return_strokes(mech, problem.return_points, turns[-1], rho[0], rho[-1],
                                        problem.poses[-1, 2])
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
            defects.append(ratio_defect(ratio[0], ratio[1], problem.ratio_bounds))
        if not margin >= problem.min_closure_margin:
            defects.append(closure_defect(margin, problem.min_closure_margin))
        judged.append(Candidate(mech, rho, defects, stroke, relative, margin, ratio))
        if not defects:
            break
    return judged[-1] if judged[-1].feasible else judged[0]


def reference_region(problem: FiveBarProblem) -> list[Candidate]:
    """Every pair of kept dyads built and judged one at a time by ``reference_candidate``, in pair order."""
    receiving, carrier = chain_families(problem)
    return [reference_candidate(problem, from_hinges(problem.poses[0], receiving.fixed[i], receiving.moving[i],
                                                     carrier.fixed[j], carrier.moving[j]), check_ranges=False)
            for i in np.flatnonzero(receiving.kept) for j in np.flatnonzero(carrier.kept)]

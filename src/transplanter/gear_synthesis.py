"""From a gear problem to a verified pair: curve, scaling, closure, tooth counts, teeth."""
from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.gear_pair import GearPairDesign, design_pair, panels
from transplanter.gear_problem import GearProblem
from transplanter.gear_teeth import PairTeeth, generate_teeth
from transplanter.pitch_curves import PeriodicSpline, PitchCurve, from_ratio


@dataclass(frozen=True)
class ToothCounts:
    """Nearest whole tooth counts with equal teeth per lobe, and what makes them exact."""

    module: float
    fractional: tuple[float, float]
    counts: tuple[int, int]
    exact_module: float            # module that makes ``counts`` exact at this size
    scale_for_module: float        # scale of the curves that makes ``counts`` exact with ``module``


@dataclass(frozen=True)
class GearResult:
    problem: GearProblem
    design: GearPairDesign
    tooth_counts: ToothCounts | None
    teeth: PairTeeth | None
    ratio_correction: float | None
    timings_s: dict


def tooth_counts(design: GearPairDesign, module: float) -> ToothCounts:
    n1, n2 = design.orders
    per_lobe = max(1, int(round(design.perimeters[0] / (np.pi * module * n1))))
    counts = (per_lobe * n1, per_lobe * n2)
    return ToothCounts(module, tuple(p / (np.pi * module) for p in design.perimeters), counts,
                       design.perimeters[0] / (np.pi * counts[0]), np.pi * module * counts[0] / design.perimeters[0])


def _ratio_curve(problem: GearProblem, center_distance: float):
    """Driver from sampled i12: closure does not depend on a (r1 = a / (1 + i)), so a ratio that does
    not close is corrected by a constant factor k when asked (seed 000 eq 12), or refused."""
    phi, ratio = problem.ratio_samples
    grid = panels(np.mod(phi, 2 * np.pi))
    turn = grid.integrate(1 / PeriodicSpline(np.mod(phi, 2 * np.pi), ratio).evaluate(grid.nodes)[0])[-1]
    target = 2 * np.pi / problem.driven_order
    factor = turn / target
    if abs(factor - 1) > 1e-9 and not problem.correct_ratio:
        raise InfeasibleError(
            f"{problem.source}: driver.ratio closes at no center distance: with r1 = a / (1 + i12) the driven gear "
            f"turns {np.degrees(turn):.6f} deg per driver turn for every a, not {np.degrees(target):.6f}; "
            f"set driver.correct = true to scale i12 by k = {factor:.9f} (seed 000 eq 12)")
    return from_ratio(phi, ratio * factor, center_distance), (factor if problem.correct_ratio else None)


def synthesize_gear(problem: GearProblem) -> GearResult:
    start = time.perf_counter()
    correction = None
    center = problem.center_distance
    if problem.ratio_samples is not None:
        driver, correction = _ratio_curve(problem, center or 1.0)
        center = center or 1.0
    else:
        driver = problem.driver
    if problem.teeth is not None:
        if problem.teeth % driver.lobes:
            raise InfeasibleError(f"{problem.source}: pair.teeth = {problem.teeth}: expected a multiple of the driver "
                                  f"order {driver.lobes} (equal teeth on every lobe)")
        perimeter = design_pair(driver, problem.driven_order, center, problem.driver_speed, problem.source).perimeters[0]
        factor = np.pi * problem.module * problem.teeth / perimeter
        driver = driver.scaled(factor)
        center = center * factor if center is not None and problem.ratio_samples is not None else None
    design = design_pair(driver, problem.driven_order, center, problem.driver_speed, problem.source)
    timings = {"pitch_curves": time.perf_counter() - start}
    counts = teeth = None
    if problem.module is not None:
        counts = tooth_counts(design, problem.module)
        if problem.teeth is not None:
            start = time.perf_counter()
            teeth = generate_teeth(design, problem.module, problem.pressure_angle, problem.source,
                                   problem.cutter, problem.shaper_teeth)
            timings["teeth"] = time.perf_counter() - start
    return GearResult(problem, design, counts, teeth, correction, timings)

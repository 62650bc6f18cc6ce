"""From a gear problem to a verified pair: curve, scaling, closure, tooth counts, teeth."""
from __future__ import annotations

import time

import numpy as np

from transplanter.api_arguments import require_problem
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.gears.composite_curve import CompositeCurve, cusps, with_exact_curvature
from transplanter.gears.composite_teeth import CompositeTeeth, generate_composite_teeth
from transplanter.gears.pair import GearPairDesign, arc_length, design_pair
from transplanter.gears.pitch_curves import from_ratio
from transplanter.gears.problem import MAX_TEETH, GearProblem, ratio_defect
from transplanter.gears.result import GearResult, ToothCounts
from transplanter.gears.teeth import PairTeeth, generate_teeth
from transplanter.geometry.turn_quadrature import panels


def tooth_counts(design: GearPairDesign, module: float) -> ToothCounts:
    n1, n2 = design.orders
    per_lobe = max(1, int(round(design.perimeters[0] / (np.pi * module * n1))))
    counts = (per_lobe * n1, per_lobe * n2)
    fractional = (design.perimeters[0] / (np.pi * module), design.perimeters[1] / (np.pi * module))
    return ToothCounts(module, fractional, counts,
                       design.perimeters[0] / (np.pi * counts[0]), np.pi * module * counts[0] / design.perimeters[0])


def _ratio_curve(problem: GearProblem, given: tuple, center_distance: float):
    """Driver from the problem's ratio i12 ``given`` (evaluator, breaks): closure does not depend on a
    (r1 = a / (1 + i12)), so a ratio that does not close is corrected by a constant factor k when asked
    (Wang et al. 2025 eq 12), or refused."""
    ratio, breaks = given
    grid = panels(breaks)
    defect = ratio_defect(ratio)
    if defect:
        raise ProblemError(f"{problem.source}: GearProblem.ratio {defect}")
    values = ratio(np.array([0.0, 2 * np.pi]))
    ends = [v[0] - v[-1] for v in values[:2]]
    if max(abs(e) for e in ends) > 1e-9 * (1 + np.abs(values[0]).max()):
        raise InfeasibleError(f"{problem.source}: driver.ratio is not periodic: i12(360 deg) - i12(0) = {-ends[0]:.3g} "
                              f"and the slope differs by {-ends[1]:.3g}; expected a function of period 360 deg")
    turn = grid.integrate(1 / ratio(grid.nodes.ravel())[0].reshape(grid.nodes.shape))[-1]
    target = 2 * np.pi / problem.driven_order
    factor = turn / target
    if abs(factor - 1) > 1e-9 and not problem.correct_ratio:
        raise InfeasibleError(
            f"{problem.source}: driver.ratio closes at no center distance: with r1 = a / (1 + i12) the driven gear "
            f"turns {np.degrees(turn):.6f} deg per driver turn for every a, not {np.degrees(target):.6f}; "
            f"set driver.correct = true to scale i12 by k = {factor:.9f} (Wang et al. 2025 eq 12)")
    return from_ratio(ratio, factor, center_distance, breaks), (factor if problem.correct_ratio else None)


def synthesize(problem: GearProblem) -> GearResult:
    """A verified gear pair: driver curve (scaled to the teeth when given), driven curve closed at
    the center distance, kinematics, tooth counts at the module, and tooth profiles when asked.

    Parameters
    ----------
    problem : GearProblem
        From ``load_problem`` / ``parse_problem`` or built directly (mm, radians).

    Returns
    -------
    GearResult

    Raises
    ------
    InfeasibleError
        When the ratio reverses, is not periodic or does not close, or the teeth do not fit the lobes.
    """
    require_problem(problem, GearProblem, "gears")
    start = time.perf_counter()
    correction = None
    center = problem.center_distance
    if problem.ratio is not None:
        driver, correction = _ratio_curve(problem, problem.ratio, center or 1.0)
        center = center or 1.0
    else:
        driver = problem.driver
    if problem.teeth is not None and problem.module is not None:    # teeth come with a module (GearProblem)
        if problem.teeth % driver.lobes:
            raise InfeasibleError(f"{problem.source}: pair.teeth = {problem.teeth}: expected a multiple of the driver "
                                  f"order {driver.lobes} (equal teeth on every lobe)")
        driven_teeth = problem.teeth * problem.driven_order // driver.lobes
        if driven_teeth > MAX_TEETH:
            raise ProblemError(f"{problem.source}: pair.teeth = {problem.teeth}: the driven gear would get "
                               f"{driven_teeth} teeth; expected at most {MAX_TEETH} on each gear (time and memory "
                               "grow with the teeth cut)")
        perimeter = arc_length(driver, panels(driver.breaks))[-1]
        factor = np.pi * problem.module * problem.teeth / perimeter
        driver = driver.scaled(factor)
        center = center * factor if center is not None and problem.ratio is not None else None
    design = design_pair(driver, problem.driven_order, center, problem.driver_speed, problem.source)
    if isinstance(driver, CompositeCurve):
        design = with_exact_curvature(design)
    timings = {"pitch_curves": time.perf_counter() - start}
    counts: ToothCounts | None = None
    teeth: PairTeeth | CompositeTeeth | None = None
    if problem.module is not None:
        counts = tooth_counts(design, problem.module)
        if problem.teeth is not None:
            start = time.perf_counter()
            if isinstance(driver, CompositeCurve) and cusps(driver):
                teeth = generate_composite_teeth(design, problem.module, problem.pressure_angle, problem.teeth,
                                                 problem.shaper_teeth, problem.source, problem.corner_pressure_angle)
            else:   # a composite without corners is cut as its smooth stretches would be: by the shaper
                cutter = "shaper" if isinstance(driver, CompositeCurve) else problem.cutter
                teeth = generate_teeth(design, problem.module, problem.pressure_angle, problem.source, cutter,
                                       problem.shaper_teeth)
            timings["teeth"] = time.perf_counter() - start
    return GearResult(problem, design, counts, teeth, correction, timings)

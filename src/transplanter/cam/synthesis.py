"""``synthesize``: a cam problem -> the cam, checked (and in design mode its smallest base circle)."""
from __future__ import annotations

import time

from transplanter.api_arguments import require_problem
from transplanter.cam.checks import check
from transplanter.cam.design import smallest_base_radius
from transplanter.cam.kinematics import evaluate
from transplanter.cam.problem import CamProblem
from transplanter.cam.result import CamResult


def synthesize(problem: CamProblem) -> CamResult:
    """The cam of ``problem``: motion, pitch curve, profile, pressure angle, curvature and their checks.

    In design mode (``problem.max_base_radius`` set) the base radius is the smallest that meets the
    pressure-angle limit without undercut (``design.smallest_base_radius``).

    Raises
    ------
    InfeasibleError
        Design mode, when no base circle up to the maximum meets the limits.
    """
    require_problem(problem, CamProblem, "cam")
    timings, start = {}, time.perf_counter()
    if problem.base_radius is None:
        base, evaluated = smallest_base_radius(problem)
        timings["design"] = time.perf_counter() - start
    else:
        base, evaluated = problem.base_radius, 1
    start = time.perf_counter()
    geometry = evaluate(problem, base)
    timings["evaluation"] = time.perf_counter() - start
    start = time.perf_counter()
    checks = check(problem, geometry)
    timings["checks"] = time.perf_counter() - start
    return CamResult(problem, geometry, checks, problem.base_radius is None, evaluated, timings)

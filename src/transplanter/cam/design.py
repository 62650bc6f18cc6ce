"""Design mode: the smallest base circle whose cam keeps the pressure angle within the limit on rises
and returns, without undercut and without the roller cutting into the profile (and, with
``limits.profile_radius_mm``, with the profile's convex radius at least that; else the smallest base
circle may leave a nearly pointed profile where the curvature binds).

Base radii are scanned from the smallest the follower allows up to ``max_base_radius`` (geometric
steps), and the first that passes is narrowed down by bisection against the last that failed. A
translating follower's pressure angle and curvature improve monotonically with the base circle, so
this finds the smallest; an oscillating follower's need not, and a base circle that passes between
two scanned sizes below the first found can be missed.
"""
from __future__ import annotations

import numpy as np

from transplanter.cam.checks import check, interference
from transplanter.cam.kinematics import evaluate
from transplanter.cam.problem import CamProblem
from transplanter.errors import InfeasibleError, ProblemError

#: Scanned base radii, and the cam angles per turn of the scan.
SCAN_SIZES, SCAN_SAMPLES = 96, 720
#: Bisection stops when the bracket is this share of the base radius.
BISECTION_SHARE = 1e-7


def base_radius_range(problem: CamProblem, largest: float) -> tuple[float, float]:
    """Open interval of base radii (mm) up to ``largest`` on which the follower sits on the cam and the roller
    fits in it."""
    follower = problem.follower
    roller = follower.roller_radius
    low, high = roller, largest
    if follower.kind == "flat_faced":
        low = 1e-6 * high
    elif follower.kind == "translating":
        low = max(low, abs(follower.offset) - roller)
    else:
        pivot, arm = follower.arm
        reach = float(np.hypot(*pivot))
        low = max(low, abs(reach - arm) - roller)
        high = min(high, reach + arm - roller)
    return low, high


def _worst(problem: CamProblem, base_radius: float, samples: int):
    """(largest |pressure angle| on rises and returns (rad), smallest convex pitch radius less the roller's (mm),
    largest roller overlap into the profile (mm)) on ``samples`` cam angles."""
    geometry = evaluate(problem, base_radius, np.linspace(0.0, 2 * np.pi, samples, endpoint=False))
    moving = np.array([s.kind != "dwell" for s in problem.segments])[geometry.segment]
    pressure = float(np.abs(geometry.pressure_angle[moving]).max())
    if problem.follower.kind == "flat_faced":                     # no convex stretch may be lost
        convex = geometry.curvature_radius
    else:
        convex = geometry.curvature_radius[geometry.curvature_radius > 0]
    sharpness = float(convex.min()) - problem.follower.roller_radius if convex.size else np.inf
    overlap = max((s.worst for s in interference(geometry, problem.follower.roller_radius)), default=0.0)
    return pressure, sharpness, overlap


def _passes(problem: CamProblem, base_radius: float, samples: int) -> bool:
    pressure, sharpness, overlap = _worst(problem, base_radius, samples)
    return pressure <= problem.pressure_limit and sharpness > 0 and sharpness >= problem.profile_radius_limit \
        and overlap == 0.0


def smallest_base_radius(problem: CamProblem) -> tuple[float, int]:
    """The smallest base radius (mm) meeting the limits, and the number of cams evaluated.

    Raises
    ------
    InfeasibleError
        When no base circle up to ``problem.max_base_radius`` meets them: says what the largest gives.
    """
    largest = problem.max_base_radius
    if largest is None:
        raise ProblemError(f"{problem.source}: max_base_radius = None: expected the largest base radius to try (mm); "
                           "a problem with its base radius given has no base circle to design")
    low, high = base_radius_range(problem, largest)
    if not low < high:
        raise InfeasibleError(f"{problem.source}: design.max_base_radius = {largest:g}: no base circle "
                              f"above {low:.6g} mm fits the roller and the follower; expected more than {low:.6g}")
    sizes = np.geomspace(low, high, SCAN_SIZES + 1)[1:]
    sizes[-1] = high * (1 - 1e-9)
    previous, evaluated = low, 0
    for size in sizes:
        evaluated += 1
        if _passes(problem, size, SCAN_SAMPLES):
            break
        previous = size
    else:
        pressure, sharpness, overlap = _worst(problem, sizes[-1], problem.samples)
        raise InfeasibleError(
            f"{problem.source}: limits.pressure_angle_deg = {np.degrees(problem.pressure_limit):g}: "
            f"no base circle up to {sizes[-1]:.6g} mm meets it without undercut (there the largest pressure angle is "
            f"{np.degrees(pressure):.3f} deg, the sharpest convex pitch radius less the roller {sharpness:.4g} mm, "
            f"the roller overlap {overlap:.4g} mm); "
            + ("raise design.max_base_radius or the limit" if high >= largest else
               "the arm cannot reach a larger base circle: move the pivot or change the arm, or raise the limit")
            + ", or lengthen the rise and return angles")
    failing, passing = previous, size
    # the scan's coarser samples missed a peak
    while not _passes(problem, passing, problem.samples) and passing < high:
        failing, passing = passing, min(passing * 1.01, high)
        evaluated += 1
    while passing - failing > BISECTION_SHARE * passing:
        middle = 0.5 * (failing + passing)
        failing, passing = (failing, middle) if _passes(problem, middle, problem.samples) else (middle, passing)
        evaluated += 1
    # The checks polish extremes between the samples, so the sampled bisection may stop a little short:
    # step up (doubling) until the polished checks pass, then bisect with them.
    if _passes_polished(problem, passing):
        return passing, evaluated
    failing, step = passing, BISECTION_SHARE * passing
    while not _passes_polished(problem, min(failing + step, high)):
        if failing + step >= high:
            raise InfeasibleError(f"{problem.source}: "
                                  f"limits.pressure_angle_deg = {np.degrees(problem.pressure_limit):g}: "
                                  f"no base circle up to {high:.6g} mm meets it without undercut; raise "
                                  "design.max_base_radius or the limit")
        failing, step = failing + step, 2 * step
        evaluated += 1
    passing = failing + step
    while passing - failing > BISECTION_SHARE * passing:
        middle = 0.5 * (failing + passing)
        failing, passing = (failing, middle) if _passes_polished(problem, middle) else (middle, passing)
        evaluated += 1
    return passing, evaluated


def _passes_polished(problem: CamProblem, base_radius: float) -> bool:
    return check(problem, evaluate(problem, base_radius)).passed

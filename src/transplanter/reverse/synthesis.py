"""Reverse design: closed tip path -> arm lengths -> inverse kinematics -> monotonicity ->
ratio split -> pitch curves -> verification by rolling (the rice-transplanter, reverse-gear-design
and cusp-pitch-curve papers).

``synthesize`` raises a ``ProblemError`` or ``InfeasibleError`` for a path it cannot use
(a curve that stops, points out of reach, impossible center distances); a path that fails
the monotonicity criterion comes back with its violations and fix hints and no train.
"""
from __future__ import annotations

import dataclasses

import numpy as np

from transplanter._generated.planetary import arm_lengths_from_extremes
from transplanter.api_arguments import require_problem, require_switch
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.generated import numpy_twin
from transplanter.geometry.closed_trajectory import ClosedTrajectory, fitted_polygon
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.arm_inverse import TOUCH_TOLERANCE, ArmMotion, solve_arm
from transplanter.reverse.carrier_frame_motion import CarrierFrameMotion
from transplanter.reverse.idler_train import design_idler_train, verify_idler_train
from transplanter.reverse.monotonicity import fix_hints, violations
from transplanter.reverse.problem import ReverseProblem
from transplanter.reverse.result import ReverseResult
from transplanter.reverse.verification import CarrierGeometry, verify_reverse
from transplanter.reverse.whole_teeth import cut_train
from transplanter.tolerance import analyse
from transplanter.trains.planetary import design_train

_arm_lengths = numpy_twin(arm_lengths_from_extremes)
#: A curve fitted to samples that comes within this fraction of the reach s + l of a reach circle
#: is taken to touch it (0.025 mm on a 250 mm reach): samples cannot say more.
SAMPLED_TOUCH = 1e-4
#: The shortest center distance of a stage, as a fraction of the carrier length s.
SMALLEST_STAGE = 1e-3


def build_trajectory(problem: ReverseProblem) -> ClosedTrajectory:
    control = problem.points if problem.kind == "control_points" else fitted_polygon(problem.points)
    trajectory = ClosedTrajectory(control)
    speed, where = trajectory.turning_speed_floor()
    scale = np.linalg.norm(np.diff(np.r_[control, control[:1]], axis=0), axis=1).mean()
    if speed < 1e-6 * scale:
        raise ProblemError(f"{problem.source}: trajectory.points: the curve stops (speed {speed:.3g} mm per unit "
                           f"parameter) at u = {where / TWO_PI:.4f}: expected a curve that keeps moving (a control "
                           "polygon that folds straight back on itself, its neighbours of a point coinciding, makes "
                           "a cusp)")
    return trajectory


def touching_reach(problem: ReverseProblem, trajectory: ClosedTrajectory, carrier_length: float,
                   arm_length: float) -> ClosedTrajectory:
    """A curve fitted to samples, moved radially so that it touches the reach circles s + l and |s - l|
    (s the carrier length, l the arm length)
    where it comes within ``SAMPLED_TOUCH`` of the reach (or the fit's own miss) of them: samples drawn
    by an arm of these lengths touch them somewhere between two samples, which a curve through the
    samples misses by a little (2.4e-5 mm with 50 samples of a 250 mm loop), and a curve that falls
    short of a reach circle by a hair makes the arm turn back there instead of straightening (or
    folding). The move shows in the fit's miss, which the report gives."""
    if problem.kind != "samples":
        return trajectory
    outer, inner = carrier_length + arm_length, abs(carrier_length - arm_length)
    allowance = max(trajectory.sample_misses(problem.points).max(), SAMPLED_TOUCH * outer)
    radii = [e.radius for e in trajectory.radial_extremes()]
    farthest, nearest = max(radii), min(radii)
    targets = (outer if abs(farthest - outer) <= allowance else farthest,
               inner if abs(nearest - inner) <= allowance else nearest)
    if targets == (farthest, nearest) or not np.linalg.norm(trajectory.control, axis=1).all():
        return trajectory
    return trajectory.radially_remapped(*targets)


def _unreachable(problem: ReverseProblem, trajectory: ClosedTrajectory, carrier_length: float, arm_length: float):
    x = np.linspace(0, TWO_PI, trajectory.count * 256, endpoint=False)
    radius = np.linalg.norm(trajectory.evaluate(x), axis=1)
    outer, inner = carrier_length + arm_length, abs(carrier_length - arm_length)
    for excess, what in ((radius - outer, f"beyond the reach s + l = {outer:.4f} mm"),
                         (inner - radius, f"inside the hole |s - l| = {inner:.4f} mm the arm cannot fold into")):
        bad = excess > TOUCH_TOLERANCE * outer
        if bad.any():
            k = np.flatnonzero(bad)
            worst = k[np.argmax(excess[k])]
            first, last = x[k[0]], x[k[-1]]
            p = trajectory.evaluate(np.array([first, last, x[worst]])) + problem.pivot
            raise InfeasibleError(
                f"{problem.source}: trajectory points from u = {first / TWO_PI:.4f} ({p[0, 0]:.6g}, {p[0, 1]:.6g}) to "
                f"u = {last / TWO_PI:.4f} ({p[1, 0]:.6g}, {p[1, 1]:.6g}) lie {what}, by up to {excess[worst]:.4g} mm "
                f"at ({p[2, 0]:.6g}, {p[2, 1]:.6g}); carrier_length = {carrier_length:g}, arm_length = {arm_length:g}; "
                f"lengths with s + l >= {radius.max():.4f} mm and |s - l| <= {radius.min():.4f} mm reach every "
                "point (leave both out for the path's own)")


def _lengths_from(extremes: tuple[float, float]) -> tuple[float, float]:
    """(s, l) from the path's farthest and nearest distances to the pivot (the rice-transplanter paper eq 1-2)."""
    carrier_length, arm_length = _arm_lengths(np.array(extremes))[0]
    return float(carrier_length), float(arm_length)


def _ratio_spread(motion: ArmMotion) -> float:
    ratio = motion.total_ratio()
    return float(ratio.max() / ratio.min())


def choose_motion(trajectory: ClosedTrajectory, carrier_length: float, arm_length: float, direction: int,
                  branch: str) -> ArmMotion:
    """The start branch asked for, or (auto) the one that passes with the smaller ratio spread."""
    starts = {"approach": (1,), "retraction": (-1,), "auto": (1, -1)}[branch]
    motions = [solve_arm(trajectory, carrier_length, arm_length, direction, b) for b in starts]
    counts = [len(violations(m)) for m in motions]
    judged = [(count, np.inf if count else _ratio_spread(m), k)
              for k, (m, count) in enumerate(zip(motions, counts, strict=True))]
    return motions[min(judged)[2]]


def carrier_geometry(problem: ReverseProblem, carrier_length: float) -> CarrierGeometry | None:
    """None for a straight carrier (sun, intermediate and planet shafts on one line): centre distances that add
    up to the carrier length, or none given, on a train other than pick-up."""
    centers = problem.center_distances
    if centers is not None and min(centers) < SMALLEST_STAGE * carrier_length:
        raise ProblemError(f"{problem.source}: train.center_distances = {list(centers)}: expected each at least "
                           f"{SMALLEST_STAGE:g} of the carrier length s = {carrier_length:.6g} mm "
                           "(a shorter stage's gears would be a thousandth of the train's size)")
    if problem.topology == "sun-idler-planet" and centers is not None \
            and abs(centers[0] - centers[1]) > 1e-9 * carrier_length:
        raise ProblemError(f"{problem.source}: train.center_distances = {list(centers)}: expected two equal "
                           "distances for sun-idler-planet (the rice-transplanter paper: the idler then makes "
                           "the sun and the planet the same curve)")
    straight = centers is None or abs(sum(centers) - carrier_length) <= 1e-9 * carrier_length
    if problem.topology != "pick-up" and straight:
        return None
    first, second = centers if centers is not None else (carrier_length / 2, carrier_length / 2)
    cosine = (carrier_length**2 - first**2 - second**2) / (2 * first * second)
    if abs(cosine) > 1:
        raise ProblemError(f"{problem.source}: train.center_distances = {[first, second]}: expected L1, L2 that can "
                           f"place the planet {carrier_length:.6g} mm from the pivot (|L1 - L2| <= s <= L1 + L2)")
    return CarrierGeometry(first, second, float(np.arccos(cosine)))


def toothed_side(geometry: CarrierGeometry, direction: int) -> CarrierGeometry:
    """The bent carrier of a toothed train: its intermediate shaft counterclockwise of pivot -> planet in the
    frame of a clockwise carrier (``trains.toothed_train``), mirrored for a counterclockwise one. A positive bend
    puts the shaft clockwise of it (``verification.rebuild_tip``: pivot -> shaft at the carrier angle minus the
    offset), so the bend takes the sign of the rotation direction."""
    return dataclasses.replace(geometry, bend=direction * abs(geometry.bend))


def synthesize(problem: ReverseProblem, tolerance: bool = True) -> ReverseResult:
    """The planetary gear train that makes the arm tip follow the problem's closed path.

    Parameters
    ----------
    problem : ReverseProblem
        From ``load_problem`` / ``parse_problem`` or built directly (mm).
    tolerance : bool, optional
        Analyse how precise the built train and arm will be (``tolerance.analyse`` with the problem's
        ``[tolerances]``; default True) when there is a train.

    Returns
    -------
    ReverseResult
        Arm lengths and motion, the monotonicity verdict; when it passes, the train, its
        round-trip verification and the tolerance analysis (``monotonic`` is False and ``train`` None when it
        fails).

    Raises
    ------
    ProblemError, InfeasibleError
        For a path that stops, points out of reach, or impossible center distances.
    """
    require_problem(problem, ReverseProblem, "reverse")
    require_switch("tolerance", tolerance)
    trajectory = build_trajectory(problem)
    radii = [e.radius for e in trajectory.radial_extremes()]
    extremes = (max(radii), min(radii))
    derived = problem.lengths is None
    if problem.lengths is None:
        carrier_length, arm_length = _lengths_from(extremes)
    else:
        carrier_length, arm_length = problem.lengths
        trajectory = touching_reach(problem, trajectory, carrier_length, arm_length)
        radii = [e.radius for e in trajectory.radial_extremes()]
        extremes = (max(radii), min(radii))
    _unreachable(problem, trajectory, carrier_length, arm_length)
    motion = choose_motion(trajectory, carrier_length, arm_length, problem.direction, problem.branch)
    found = violations(motion)
    if found:
        return ReverseResult(problem, trajectory, extremes, derived, motion, found,
                             fix_hints(trajectory, motion, _lengths_from(extremes)))
    geometry = carrier_geometry(problem, carrier_length)
    relative = CarrierFrameMotion(motion)
    if problem.topology == "sun-idler-planet":
        idler = design_idler_train(relative, carrier_length / 2, problem.source)
        result = ReverseResult(problem, trajectory, extremes, derived, motion, [], [], relative, None, idler,
                               verify_idler_train(motion, idler))
        return _analysed(result) if tolerance else result
    exponent = problem.peak_to_valley if problem.split == "peak_to_valley" else 0.5
    toothed, teeth_note = cut_train(problem, relative, carrier_length, exponent)
    if toothed is None:
        halves = (carrier_length / 2, carrier_length / 2)
        centers = (geometry.first, geometry.second) if geometry else (problem.center_distances or halves)
        train = design_train(relative, centers, problem.source, exponent)
    else:
        train = toothed.train
        geometry = carrier_geometry(dataclasses.replace(problem, center_distances=train.center_distances),
                                    carrier_length)
        if geometry is not None:      # the shaft on the side the toothed layout puts it (``toothed_side``)
            geometry = toothed_side(geometry, problem.direction)
    result = ReverseResult(problem, trajectory, extremes, derived, motion, [], [], relative, geometry, train,
                           verify_reverse(motion, train, geometry), toothed=toothed, teeth_note=teeth_note)
    return _analysed(result) if tolerance else result


def _analysed(result: ReverseResult) -> ReverseResult:
    """``result`` with its tolerance analysis, or with the reason there is none (a dimension without a default
    tolerance the problem does not give), which does not fail the design."""
    try:
        return dataclasses.replace(result, tolerance=analyse(result, result.problem.tolerances))
    except ProblemError as error:
        return dataclasses.replace(result, tolerance_note=f"no tolerance analysis: {error}")

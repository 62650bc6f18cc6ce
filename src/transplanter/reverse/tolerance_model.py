"""The built reverse design (an arm on the planet of a planetary train: four gears, or sun, idler and planet) as
a function of its manufactured dimensions, for the tolerance analysis: the arm tip is the analysis's P, the arm's
angle its plate angle.

Dimensions (the report's names; mm or deg):

- ``arm_length`` (l) and the carrier's ``center_distance_L1`` (pivot to the intermediate shaft),
  ``center_distance_L2`` (intermediate shaft to the planet) and ``carrier_bend`` (the turn from the first to
  the second, 0 on a straight carrier): they place the carrier's three holes, so the carrier length s follows;
  ISO 2768-m by size (the bend by the shorter of L1 and L2);
- ``clearance_pivot_x`` / ``_y``, ``clearance_planet_x`` / ``_y``: where the carrier's and the planet's shafts
  sit in their holes, constant offsets in the frame's axes within the radial play
  ``tolerance.dimensions.HINGE_PLAY_MM`` (the problem sets no shaft diameter to take an H7/g6 fit from);
- ``backlash_stage_1`` / ``_2`` and ``phase_<gear>``: the gears' lost motion and assembly phases (deg,
  ``tolerance.planetary_gears``), at the standard pressure angle ``PRESSURE_ANGLE_DEG``.

Motion. The carrier's axis, pivot to planet, turns with the drive as designed, theta(c) = theta(0) + d c (d
the rotation direction); the planet's turn against it comes from ``planetary_gears.planet_turn`` in the sense
the sun turns against the carrier (-d), so the arm points along theta + gamma(0) - d rho. The tip follows by
the generated eq (15) of the cusp-pitch-curve paper (the synthesis's round trip rebuilds the tip with it) from
L1, L2, l and the carrier's holes, plus the shafts' offsets. A sun-idler-planet train (three gears, a straight
carrier with L1 = L2) turns its planet the same way (``tolerance.idler_gears``), the idler standing for both
intermediate gears, with no intermediate phases.

``built_motion`` is written once over a backend: CasADi (one turn, symbolic, for the exact Jacobian) and
numpy (N built mechanisms by T turns at once, for the Monte Carlo).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.planetary import pickup_tip
from transplanter.errors import ProblemError
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.idler_train import IdlerTrain
from transplanter.tolerance.dimensions import Dimension, hinge_plays
from transplanter.tolerance.idler_gears import IDLER_GEAR_DIMENSION_NAMES, IDLER_GEARS, idler_gear_rows
from transplanter.tolerance.iso2768 import angular_limit_deg, linear_limit_mm
from transplanter.tolerance.model import ToleranceModel, backend_motion
from transplanter.tolerance.planetary_gears import (
    BACKLASH_GRID,
    GEAR_DIMENSION_NAMES,
    GEARS,
    gear_dimensions,
    gear_rows,
    planet_turn,
)
from transplanter.trains.planetary import PlanetaryTrain

#: Pressure angle of the teeth (deg): the standard basic rack (ISO 53); the reverse problem sets none.
PRESSURE_ANGLE_DEG = 20.0
#: Whole-turn samples the trajectory band and the path accuracy are judged on (3 deg apart).
TURN_SAMPLES = 120
#: How far a built tip may stray from the path unless ``[tolerances]`` says (``PATH_ACCURACY_KEY``, mm), as a
#: fraction of the reach s + l: 2.5 mm on the rice-transplanter paper's 254 mm arm, the order of a seedling's
#: stem.
PATH_ACCURACY, PATH_ACCURACY_KEY = 0.01, "path_accuracy_mm"
HINGES = ("pivot", "planet")
LINKS = ("arm_length", "center_distance_L1", "center_distance_L2")
#: Rows of the motion: the tip (mm, in the problem's frame) and the arm's angle (rad).
ROWS = ("x_tip", "y_tip", "arm_angle")
DIMENSION_NAMES = (*LINKS, "carrier_bend", *(f"clearance_{h}_{axis}" for h in HINGES for axis in "xy"),
                   *GEAR_DIMENSION_NAMES)
IDLER_DIMENSION_NAMES = (*DIMENSION_NAMES[:-len(GEAR_DIMENSION_NAMES)], *IDLER_GEAR_DIMENSION_NAMES)


def _bend(result) -> float:
    """The carrier's designed bend (rad): 0 on a straight carrier."""
    return 0.0 if result.geometry is None else float(result.geometry.bend)


def built_motion(lib, result, v: dict, g) -> tuple:
    """The ``ROWS`` of the built mechanism with dimensions ``v`` (by name, in their units) at the turns of gear
    rows ``g`` (``planetary_gears.gear_rows``), on a backend ``lib`` (``generated.CASADI`` or ``.NUMPY``)."""
    motion, train, d = result.motion, result.train, result.motion.direction
    rad = np.pi / 180
    first, second, bend = v["center_distance_L1"], v["center_distance_L2"], v["carrier_bend"] * rad
    offset = lib.atan2(second * lib.sin(bend), first + second * lib.cos(bend))   # pivot->shaft to pivot->planet
    bend_0 = _bend(result)
    a1_0, a2_0 = center_distances(train)
    offset_0 = np.arctan2(a2_0 * np.sin(bend_0), a1_0 + a2_0 * np.cos(bend_0))
    length = lib.sqrt(first**2 + second**2 + 2 * first * second * lib.cos(bend))
    # seen against the sun's turn (-d), the shaft lies d offset from the carrier's axis
    turn = planet_turn(lib, g, (a1_0, a2_0), np.radians(PRESSURE_ANGLE_DEG), (motion.carrier_length, d * offset_0),
                       (length, first, d * offset / rad), v)
    theta = motion.theta_grid[0] + d * g[0]
    arm = theta + motion.gamma_grid[0] - d * turn
    segment = theta - offset
    tip = pickup_tip(lib, [first, second, v["arm_length"]], [segment, bend, arm - segment - bend, 0.0])[0]
    shift = [sum(v[f"clearance_{h}_{axis}"] for h in HINGES) for axis in "xy"]
    pivot = result.problem.pivot
    return tip[0] + pivot[0] + shift[0], tip[1] + pivot[1] + shift[1], arm


def center_distances(train: PlanetaryTrain | IdlerTrain) -> tuple[float, float]:
    """The designed center distances of the train's two stages (mm): an idler's are equal."""
    return (train.center_distance,) * 2 if isinstance(train, IdlerTrain) else train.center_distances


def _gear_rows(result, turns: np.ndarray) -> np.ndarray:
    """``planetary_gears.gear_rows`` of the design's train (four gears or an idler) at carrier turns (rad)."""
    if isinstance(result.train, IdlerTrain):
        return idler_gear_rows(result.train, turns)
    return gear_rows(result.relative, result.train, turns)


def dimension_names(topology: str) -> tuple[str, ...]:
    """The toleranced dimensions of a train of ``topology``, in order."""
    return IDLER_DIMENSION_NAMES if topology == "sun-idler-planet" else DIMENSION_NAMES


def _dimensions(result) -> tuple[Dimension, ...]:
    """Every toleranced dimension with its nominal value and default tolerance; a length or bend the problem's
    ``[tolerances]`` gives is not looked up in ISO 2768 (which has none below 0.5 mm or above 4 m)."""
    train, given = result.train, result.problem.tolerances.tolerances
    a1, a2 = center_distances(train)
    nominal = {"arm_length": result.motion.arm_length, "center_distance_L1": a1, "center_distance_L2": a2}
    links = [Dimension(name, float(value), given[name] if name in given else linear_limit_mm(value), "mm", "ISO 2768-m")
             for name, value in nominal.items()]
    bend = Dimension("carrier_bend", float(np.degrees(_bend(result))),
                     given["carrier_bend"] if "carrier_bend" in given else angular_limit_deg(min(a1, a2)), "deg",
                     "ISO 2768-m, shorter leg")
    play = hinge_plays(dict.fromkeys(HINGES))
    gears = gear_dimensions(_gear_rows(result, BACKLASH_GRID), (a1, a2), result.problem.module,
                            np.radians(PRESSURE_ANGLE_DEG), IDLER_GEARS if isinstance(train, IdlerTrain) else GEARS)
    return (*links, bend, *play, *gears)


@dataclass(frozen=True)
class PathAccuracy:
    """Which of N built mechanisms' tips stray further than ``tolerance_mm`` somewhere over the turn from the
    path point the designed tip is at at that turn (the carrier turned as far): the accuracy the trajectory's
    bands measure, timing included."""

    path: np.ndarray            # (2, T) the path at the whole turn's samples, mm
    whole_turn: slice
    tolerance_mm: float

    def __call__(self, motion: np.ndarray, dimensions: np.ndarray) -> dict[str, np.ndarray]:
        miss = np.linalg.norm(motion[:, :2, self.whole_turn] - self.path[None], axis=1)
        return {"path accuracy": ~(np.max(miss, axis=1) <= self.tolerance_mm)}


def key_points(result) -> tuple[tuple[str, ...], np.ndarray]:
    """The path's farthest and nearest points from the pivot (where the arm is most stretched and most
    folded): their labels and the carrier turns at them (rad)."""
    extremes = result.trajectory.radial_extremes()
    chosen = [max(extremes, key=lambda e: e.radius), min(extremes, key=lambda e: e.radius)]
    return (("farthest", "nearest"),
            np.mod(result.motion.carrier_turn_at(np.array([e.parameter for e in chosen])), TWO_PI))


def path_accuracy_mm(result) -> float:
    """How far (mm) a built tip may stray from the path: the problem's ``[tolerances]`` path_accuracy_mm, else
    ``PATH_ACCURACY`` of the reach s + l."""
    given = result.problem.path_accuracy_mm
    return PATH_ACCURACY * (result.motion.carrier_length + result.motion.arm_length) if given is None else given


def tolerance_model(result) -> ToleranceModel:
    """The designed train and arm of a ``ReverseResult`` as a function of its manufactured dimensions: the key
    points first (``key_points``), then ``TURN_SAMPLES`` turns over the whole turn; its hard condition the path
    accuracy (``PathAccuracy``, ``path_accuracy_mm``)."""
    if result.train is None:
        raise ProblemError(f"{result.source}: trajectory.points: the tolerance analysis needs a train, which a path "
                           "that fails the monotonicity criterion does not have")
    labels, key_turns = key_points(result)
    whole = np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)
    turns = np.r_[key_turns, whole]
    rows = _gear_rows(result, turns)
    at_turn, sampled = backend_motion("reverse_built_motion", built_motion, result,
                                      dimension_names(result.problem.topology), rows)
    motion = result.motion
    path = (result.trajectory.evaluate(motion.parameter_at(whole)) + result.problem.pivot).T
    problem = result.problem
    whole_turn = slice(len(turns) - TURN_SAMPLES, None)
    return ToleranceModel(problem.title or problem.source, _dimensions(result), at_turn, rows,
                          sampled, np.degrees(turns), labels, whole_turn,
                          PathAccuracy(path, whole_turn, path_accuracy_mm(result)), point="arm tip",
                          angle="arm angle")

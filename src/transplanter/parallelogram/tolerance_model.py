"""The built onion transplanter as a function of its manufactured dimensions, for the tolerance analysis.

Dimensions (the names of the report's design table where they are there; mm or deg):

- the parallelogram's links ``l1`` (crank O2A), ``l1_DB`` (its parallel crank DB), ``l2`` (coupler AB),
  ``l2_O2D`` (the frame's O2D), and the tool's ``l5`` (BC) and ``l6`` (CE); the gears' ``center_distance``
  (O1 to O2, the driven shaft that carries the crank): ISO 2768-m by size;
- ``clearance_<hinge>_x`` / ``_y`` for O2, A, B, D: where the pin sits in its hole, a constant offset in the
  frame's axes, within the radial play ``tolerance.dimensions.HINGE_PLAY_MM`` (the problem sets no shaft
  diameter to take an H7/g6 fit from);
- ``backlash``: the driven gear's lost motion (deg), within half the ISO/TR 10064-2 minimum normal backlash
  2/3 (0.06 + 0.0005 a + 0.03 m) mm over the driven gear's mean pitch radius;
- ``phase_driver`` (the driver gear on its shaft) and ``alpha_deg`` (the crank on the driven shaft, the
  paper's initial phase alpha): assembly phases, +-``PHASE_DEG``.

Motion. The driver turns by phi1 less its phase; the driven gear follows by the generated eq (4) closed form
(``limacon_driven_angle``, the synthesis's own), lagging by the lost motion plus the backlash a larger centre
distance opens, delta a tan(pressure angle) / r2 (r2 = a - r1 at the contact; taken up against the load,
which resists the motion). The crank turns with it at the paper's crank phase; A = O2 + l1 (cos, sin) with
the plays of O2 and A. The parallel crank DB is taken to turn parallel to O2A (what the parallelogram holds
away from its change points, where a rigid model of mismatched links cannot close), so the coupler's
direction is that of B - A = (O2D, 0) + (DB - O2A) (cos, sin) + the plays of D and B less those of O2 and A,
and the tool point is E = A + (AB + l5, -l6) turned by it (eq 18 with the coupler's attitude). Rows: E in the
field frame (the machine's travel added), and the coupler's attitude (rad, 0 when built exactly) as the
"plate angle".

The planting depth of each built mechanism is measured as ``trajectory.measure`` does (the lowest point,
the stretch around it where |X_E - X_E(t_E)| <= the depth window, its height) on a fine grid of turns around
the design's depth stretch: the lowest point refined by a parabola, the stretch's ends by linear
interpolation.

``built_motion`` is written once over a backend: CasADi (one turn, symbolic, for the exact Jacobian) and
numpy (N built mechanisms by T turns at once, for the Monte Carlo).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.parallelogram import limacon_driven_angle
from transplanter.generated import NUMPY
from transplanter.geometry.planar import TWO_PI
from transplanter.parallelogram.evaluation import EVALUATION_SAMPLES
from transplanter.parallelogram.kinematics import Mechanisms, mechanisms
from transplanter.parallelogram.problem import ParallelogramProblem
from transplanter.parallelogram.trajectory import measure
from transplanter.tolerance.dimensions import Dimension, hinge_plays
from transplanter.tolerance.iso2768 import linear_limit_mm
from transplanter.tolerance.model import ToleranceModel, backend_motion

#: Assembly phase of each gear and of the crank on its shaft (deg).
PHASE_DEG = 0.1
#: Whole-turn samples the trajectory band is judged on (3 deg apart).
TURN_SAMPLES = 120
#: Turns on which the depth of a built mechanism is measured: the design's depth stretch widened by
#: ``DEPTH_MARGIN`` of its width either side, ``DEPTH_SAMPLES`` turns.
DEPTH_SAMPLES, DEPTH_MARGIN = 601, 0.5
HINGES = ("O2", "A", "B", "D")
LINKS = ("l1", "l1_DB", "l2", "l2_O2D", "l5", "l6", "center_distance")
#: Rows of the motion: E in the field frame (mm) and the coupler's attitude (rad).
ROWS = ("x_E", "y_E", "coupler_angle")
DIMENSION_NAMES = (*LINKS, *(f"clearance_{h}_{axis}" for h in HINGES for axis in "xy"), "backlash", "phase_driver",
                   "alpha_deg")
KEY_LABELS = ("depth stretch start", "planting", "depth stretch end")


def minimum_backlash_mm(center_distance: float, module: float) -> float:
    """ISO/TR 10064-2's minimum normal backlash (mm) for a centre distance and module (mm)."""
    return 2 / 3 * (0.06 + 0.0005 * center_distance + 0.03 * module)


def _unit(lib, angle):
    return lib.cos(angle), lib.sin(angle)


def _turn_rows(mech: Mechanisms, phi1: np.ndarray) -> np.ndarray:
    """Per driver angle (any turn): the angle within its turn, the crank's phase with the whole turns' driven
    rotation, and the machine's travel since phi1 = 0 (mm); (3, T)."""
    laps = np.floor(phi1 / TWO_PI)
    phase = mech.crank_phase[0] + mech.conventions.crank_sense * laps * mech.driven_turn[0]
    return np.vstack([phi1 - TWO_PI * laps, phase, mech.forward_velocity * phi1 / mech.driver_speed])


@dataclass(frozen=True)
class BuiltDesign:
    """The design (one mechanism) as built: its gears scaled by ``gear_scale`` to whole teeth (the motion is
    unchanged: it depends on b/l and a/l only), with the pair's pressure angle (rad) and module (mm)."""

    mech: Mechanisms
    gear_scale: float
    pressure_angle: float
    module: float

    @property
    def center_distance(self) -> float:
        """The built pair's centre distance (mm)."""
        return self.gear_scale * float(self.mech.center_distance[0])


def built_motion(lib, built: BuiltDesign, v: dict, turn) -> tuple:
    """The ``ROWS`` of the built mechanism with dimensions ``v`` (by name, in their units) at the turns of
    ``turn`` (``_turn_rows``), on a backend ``lib`` (``generated.CASADI`` or ``generated.NUMPY``)."""
    mech, rad = built.mech, np.pi / 180
    phi1, crank_phase, travel = turn
    a0, sense = float(mech.center_distance[0]), mech.conventions.crank_sense
    pitch = [float(mech.base_radius[0]), float(mech.amplitude[0]), float(mech.m11[0]), float(mech.m12[0])]
    (phi2,), (r1,) = limacon_driven_angle(lib, [phi1 - v["phase_driver"] * rad], pitch, [a0])
    moved = v["center_distance"] - built.center_distance
    lag = v["backlash"] * rad + moved * np.tan(built.pressure_angle) / (built.gear_scale * (a0 - r1))
    theta = crank_phase + sense * (phi2 - lag) - sense * (v["alpha_deg"] * rad - float(mech.alpha[0]))
    u = _unit(lib, theta)
    pivot = (a0 + moved + mech.pivot_offset[0], mech.pivot_offset[1])
    play = {axis: {h: v[f"clearance_{h}_{axis}"] for h in HINGES} for axis in "xy"}
    a = [pivot[i] + play[axis]["O2"] + play[axis]["A"] + v["l1"] * u[i] for i, axis in enumerate("xy")]
    coupler = [(v["l2_O2D"] if axis == "x" else 0.0) + (v["l1_DB"] - v["l1"]) * u[i]
               + play[axis]["D"] + play[axis]["B"] - play[axis]["O2"] - play[axis]["A"] for i, axis in enumerate("xy")]
    attitude = lib.atan2(coupler[1], coupler[0])
    c, s = _unit(lib, attitude)
    reach, drop = v["l2"] + v["l5"], -v["l6"]
    return a[0] + c * reach - s * drop + travel, a[1] + s * reach + c * drop, attitude


def _dimensions(built: BuiltDesign) -> tuple[Dimension, ...]:
    """Every toleranced dimension with its nominal value and default tolerance."""
    mech = built.mech
    nominal = {"l1": mech.l1[0], "l1_DB": mech.l1[0], "l2": mech.l2[0], "l2_O2D": mech.l2[0], "l5": mech.l5[0],
               "l6": mech.l6[0], "center_distance": built.center_distance}
    links = [Dimension(name, float(value), linear_limit_mm(value), "mm", "ISO 2768-m")
             for name, value in nominal.items()]
    play = hinge_plays(dict.fromkeys(HINGES))
    r1 = limacon_driven_angle(NUMPY, [np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)],
                              [float(mech.base_radius[0]), float(mech.amplitude[0]), float(mech.m11[0]),
                               float(mech.m12[0])], [float(mech.center_distance[0])])[1][0]
    driven_radius = built.gear_scale * np.mean(mech.center_distance[0] - r1)
    backlash = Dimension("backlash", 0.0,
                         float(np.degrees(minimum_backlash_mm(built.center_distance, built.module) / 2
                                          / (np.cos(built.pressure_angle) * driven_radius))),
                         "deg", "half the minimum backlash")
    phases = [Dimension("phase_driver", 0.0, PHASE_DEG, "deg", "assembly phase"),
              Dimension("alpha_deg", float(np.degrees(mech.alpha[0])), PHASE_DEG, "deg", "assembly phase")]
    return (*links, *play, backlash, *phases)


def depth_on_grid(x: np.ndarray, y: np.ndarray, window: float) -> np.ndarray:
    """Planting depth H (mm) of N paths sampled on a grid of turns around their lowest point (x, y: (N, D),
    field frame): the lowest point refined by a parabola through its grid neighbours, the connected stretch
    around it where |x - x_lowest| <= ``window``, its ends by linear interpolation, and the stretch's largest
    height above the lowest point. NaN where the stretch reaches the end of the grid."""
    count, samples = x.shape
    rows = np.arange(count)
    k = np.clip(np.argmin(y, axis=1), 1, samples - 2)
    y0, y1, y2 = y[rows, k - 1], y[rows, k], y[rows, k + 1]
    x0, x1, x2 = x[rows, k - 1], x[rows, k], x[rows, k + 1]
    curvature = y0 - 2 * y1 + y2
    s = np.clip(np.divide(y0 - y2, 2 * curvature, out=np.zeros_like(y1), where=curvature > 0), -1.0, 1.0)
    lowest_y = y1 - (y0 - y2) * s / 4
    lowest_x = x1 + s * (x2 - x0) / 2 + s**2 * (x0 - 2 * x1 + x2) / 2
    gap = np.abs(x - lowest_x[:, None]) - window
    columns = np.arange(samples)[None, :]
    outside = (gap > 0) & (columns != k[:, None])
    before = np.max(np.where(outside & (columns < k[:, None]), columns, -1), axis=1)
    after = np.min(np.where(outside & (columns > k[:, None]), columns, samples), axis=1)
    reached = (before < 0) | (after >= samples)
    on_run = (columns > before[:, None]) & (columns < after[:, None])
    top = np.max(np.where(on_run, y, -np.inf), axis=1)
    for out, inner in ((before, before + 1), (after, after - 1)):
        out, inner = np.clip(out, 0, samples - 1), np.clip(inner, 0, samples - 1)
        g_out, g_in = gap[rows, out], gap[rows, inner]
        share = np.divide(g_out, g_out - g_in, out=np.zeros_like(g_out), where=g_out > g_in)
        top = np.maximum(top, y[rows, out] + share * (y[rows, inner] - y[rows, out]))
    return np.where(reached, np.nan, top - lowest_y)


@dataclass(frozen=True)
class HardConditions:
    """Which of N built mechanisms violate the onion problem's hard condition: the planting depth within
    its band (a depth that cannot be measured on the grid, or a NaN motion, violates it)."""

    problem: ParallelogramProblem
    depth_turns: slice

    def depths(self, motion: np.ndarray) -> np.ndarray:
        """The planting depth (mm) of each built mechanism (N,)."""
        return depth_on_grid(motion[:, 0, self.depth_turns], motion[:, 1, self.depth_turns], self.problem.depth_window)

    def __call__(self, motion: np.ndarray, dimensions: np.ndarray) -> dict[str, np.ndarray]:
        low, high = self.problem.depth_band
        depth = self.depths(motion)
        return {"depth band": ~((depth >= low) & (depth <= high))}


def tolerance_model(problem: ParallelogramProblem, design: dict, built_center_distance: float) -> ToleranceModel:
    """The design (mm, rad) of an onion problem as a function of its manufactured dimensions, its gears built
    at ``built_center_distance`` (mm): the key poses (the ends of the depth stretch and the planting instant)
    first, then ``TURN_SAMPLES`` turns over the whole turn, then ``DEPTH_SAMPLES`` turns around the depth
    stretch."""
    mech = mechanisms(problem, design)
    measured = measure(mech, problem.depth_window, EVALUATION_SAMPLES)
    start, end = measured.window[:, 0]
    widen = DEPTH_MARGIN * (end - start)
    turns = np.r_[start, measured.planting_angle[0], end, np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False),
                  np.linspace(start - widen, end + widen, DEPTH_SAMPLES)]
    built = BuiltDesign(mech, built_center_distance / float(mech.center_distance[0]), problem.pressure_angle,
                        problem.module)
    rows = _turn_rows(mech, turns)
    at_turn, sampled = backend_motion("parallelogram_built_motion", built_motion, built, DIMENSION_NAMES, rows)
    whole = slice(len(KEY_LABELS), len(KEY_LABELS) + TURN_SAMPLES)
    return ToleranceModel(problem.title or problem.source, _dimensions(built), at_turn, rows, sampled,
                          np.degrees(turns), KEY_LABELS, whole,
                          HardConditions(problem, slice(whole.stop, None)), point="planting point E",
                          angle="tool angle")

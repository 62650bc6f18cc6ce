"""The built five-bar as a function of its manufactured dimensions, for the tolerance analysis.

Dimensions (the names of the report's design table where they are there; mm or deg):

- link lengths ``carrier_length_OA``, ``rod_length_AF``, ``receiving_plate_length_BE`` and the push plate's
  triangle ``plate_link_length_EF``, ``push_plate_EP``, ``push_plate_FP``; the frame's ``frame_length_OB``
  (B stays on its designed direction from O); the carrier's ``center_distance_a1`` (O to the intermediate
  shaft) and ``bend_angle`` (A-O-shaft): with OA they place the three holes of the carrier, so a2 follows;
  ISO 2768-m by size (the bend angle by its shorter leg);
- ``clearance_<hinge>_x`` / ``_y`` for O, A, F, E, B: where the pin sits in its hole, a constant offset in the
  frame's axes, within the radial play of an H7/g6 fit on the shaft the drawings give the hinge
  (``fivebar.shafts``: O the sun's fixed shaft, A the planet's, F, E and B the hinge pins; ``SHAFT_OF_HINGE``);
- ``backlash_stage_1`` / ``_2`` and ``phase_<gear>``: the gears' lost motion and assembly phases (deg,
  ``tolerance.planetary_gears``).

Motion. The gears map the carrier turn c to the rod's angle relative to the carrier
(``tolerance.planetary_gears.planet_turn``: the line of centres turned by the bend's error, the backlash taken
up against the load, the phases), the rod sitting on the planet at its phase. The
linkage then closes through the generated eq (9) root on the design's branch (exact: eq (8) has no
residual there but rounding), with the hinge offsets carried as shifts of F and B.

``built_motion`` is written once over a backend: CasADi (one turn, symbolic, for the exact Jacobian) and
numpy (N built mechanisms by T turns at once, for the Monte Carlo).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from transplanter._generated.fivebar import (
    fivebar_closure_margin,
    fivebar_half_angle_quadratic,
    fivebar_transmission_margin,
)
from transplanter.geometry.planar import TWO_PI, cross
from transplanter.tolerance.dimensions import Dimension, hinge_plays
from transplanter.tolerance.iso2768 import angular_limit_deg, linear_limit_mm
from transplanter.tolerance.model import ToleranceModel, backend_motion
from transplanter.tolerance.planetary_gears import (
    BACKLASH_GRID,
    GEAR_DIMENSION_NAMES,
    gear_dimensions,
    gear_rows,
    planet_turn,
)

#: The shaft of ``fivebar.shafts`` each hinge turns on.
SHAFT_OF_HINGE = {"O": "sun", "A": "planet", "F": "hinge", "E": "hinge", "B": "hinge"}
#: Whole-turn samples the conditions and the trajectory band are judged on (3 deg apart).
TURN_SAMPLES = 120
HINGES = ("O", "A", "F", "E", "B")
LINKS = ("carrier_length_OA", "rod_length_AF", "plate_link_length_EF", "receiving_plate_length_BE",
         "push_plate_EP", "push_plate_FP", "frame_length_OB", "center_distance_a1")
#: Rows of the motion: P (mm), plate angle (rad), sin^2(EBF), sin^2(BEF), x of E and F (mm).
ROWS = ("x_P", "y_P", "plate_angle", "closure_margin", "transmission_margin", "x_E", "x_F")
DIMENSION_NAMES = (*LINKS, "bend_angle", *(f"clearance_{h}_{axis}" for h in HINGES for axis in "xy"),
                   *GEAR_DIMENSION_NAMES)


def _unit(lib, angle):
    return lib.cos(angle), lib.sin(angle)


def built_motion(lib, result, v: dict, g) -> tuple:
    """The ``ROWS`` of the built mechanism with dimensions ``v`` (by name, in their units) at the turns of gear
    rows ``g`` (``planetary_gears.gear_rows``), on a backend ``lib`` (``generated.CASADI`` or ``generated.NUMPY``)."""
    mech, toothed, relative = result.design.mech, result.toothed, result.design.relative_angle
    nominal = (mech.carrier_length, toothed.bend_angle)
    carrier = (v["carrier_length_OA"], v["center_distance_a1"], v["bend_angle"])
    rho = relative.rho1 + planet_turn(lib, g, toothed.train.center_distances, toothed.pressure_angle, nominal,
                                      carrier, v)
    c = g[0]

    # the linkage, closed by the generated eq (9) root on the design's branch, hinge offsets as shifts of F and B
    theta1 = mech.carrier_angle - c
    theta2 = theta1 + rho
    shift = [sum(v[f"clearance_{h}_{axis}"] for h in ("O", "A", "F")) for axis in "xy"]
    b_dir = np.asarray(mech.hinge_b) / np.hypot(*mech.hinge_b)
    hinge_b = [v["frame_length_OB"] * b_dir[i] + v[f"clearance_B_{axis}"] + v[f"clearance_E_{axis}"]
               for i, axis in enumerate("xy")]
    b_rel = [hinge_b[i] - shift[i] for i in range(2)]
    l1, l2, l3, l4 = (v[name] for name in ("carrier_length_OA", "rod_length_AF", "plate_link_length_EF",
                                           "receiving_plate_length_BE"))
    lengths = [l1, l2, l3, l4, lib.sqrt(b_rel[0] ** 2 + b_rel[1] ** 2)]
    crank = [theta1, theta2, lib.atan2(b_rel[1], -b_rel[0])]
    qa, qb, qc = fivebar_half_angle_quadratic(lib, lengths, crank)[0]
    root = lib.sqrt(qb**2 - 4 * qa * qc)
    f_rel = [l1 * u1 + l2 * u2 for u1, u2 in zip(_unit(lib, theta1), _unit(lib, theta2), strict=True)]
    first_root = 2 * lib.atan2(-qb + root, 2 * qa)
    e_first = _unit(lib, first_root)
    on_branch = ((f_rel[0] - b_rel[0]) * e_first[1] - (f_rel[1] - b_rel[1]) * e_first[0]) * mech.branch > 0
    theta4 = lib.if_else(on_branch, first_root, 2 * lib.atan2(-qb - root, 2 * qa))
    e = [hinge_b[i] + l4 * w for i, w in enumerate(_unit(lib, theta4))]
    f = [f_rel[i] + shift[i] for i in range(2)]

    # the push plate: P from E and F by its triangle, on the designed side of EF
    plate_axis = np.asarray(mech.f_local) - mech.e_local
    side = np.sign(cross(plate_axis, -np.asarray(mech.e_local)))
    ef, ep, fp = v["plate_link_length_EF"], v["push_plate_EP"], v["push_plate_FP"]
    cos_e = (ef**2 + ep**2 - fp**2) / (2 * ef * ep)
    direction = lib.atan2(f[1] - e[1], f[0] - e[0])
    to_p = _unit(lib, direction + side * lib.atan2(lib.sqrt(1 - cos_e**2), cos_e))
    closure = fivebar_closure_margin(lib, lengths, crank)[0][0]
    transmission = fivebar_transmission_margin(lib, lengths, crank)[0][0]
    return (e[0] + ep * to_p[0], e[1] + ep * to_p[1], direction - np.arctan2(plate_axis[1], plate_axis[0]),
            closure, transmission, e[0], f[0])


def _dimensions(result) -> tuple[Dimension, ...]:
    """Every toleranced dimension with its nominal value and default tolerance."""
    mech, toothed = result.design.mech, result.toothed
    a1, a2 = toothed.train.center_distances
    nominal = {"carrier_length_OA": mech.carrier_length, "rod_length_AF": mech.rod_length,
               "plate_link_length_EF": mech.link_length, "receiving_plate_length_BE": mech.receiving_length,
               "push_plate_EP": mech.ep, "push_plate_FP": mech.fp, "frame_length_OB": np.hypot(*mech.hinge_b),
               "center_distance_a1": a1}
    links = [Dimension(name, float(value), linear_limit_mm(value), "mm", "ISO 2768-m")
             for name, value in nominal.items()]
    bend = Dimension("bend_angle", float(np.degrees(toothed.bend_angle)),
                     angular_limit_deg(min(a1, mech.carrier_length)), "deg", "ISO 2768-m, shorter leg")
    play = hinge_plays({h: result.shafts.shafts[SHAFT_OF_HINGE[h]].diameter for h in HINGES})
    gears = gear_dimensions(gear_rows(result.design.relative_angle, toothed.train, BACKLASH_GRID),
                            toothed.train.center_distances, toothed.module, toothed.pressure_angle)
    return (*links, bend, *play, *gears)


@dataclass(frozen=True)
class HardConditions:
    """Which of N built mechanisms violate each hard condition of the five-bar problem."""

    result: Any
    key_count: int
    return_count: int

    def __call__(self, motion: np.ndarray, dimensions: np.ndarray) -> dict[str, np.ndarray]:
        problem, names = self.result.problem, DIMENSION_NAMES
        returns = slice(self.key_count, self.key_count + self.return_count)
        found = {}
        value = {"ep": dimensions[:, names.index("push_plate_EP")], "fp": dimensions[:, names.index("push_plate_FP")],
                 "x_e": motion[:, ROWS.index("x_E"), 0], "x_f": motion[:, ROWS.index("x_F"), 0]}
        for key, (low, high) in problem.ranges.items():
            found[f"ranges.{key}"] = ~((value[key] >= low) & (value[key] <= high))
        found["closure margin"] = ~(np.min(motion[:, ROWS.index("closure_margin")], axis=1)
                                    >= problem.min_closure_margin)
        if problem.min_transmission_angle is not None:
            found["transmission angle"] = ~(np.min(motion[:, ROWS.index("transmission_margin")], axis=1)
                                            >= np.sin(problem.min_transmission_angle) ** 2)
        if self.return_count:
            miss = np.linalg.norm(motion[:, :2, returns] - problem.return_points.T[None], axis=1)
            found["return tolerance"] = ~(np.max(miss, axis=1) <= problem.return_tolerance_mm)
        return found


def tolerance_model(result) -> ToleranceModel:
    """The designed five-bar of a ``FiveBarResult`` as a function of its manufactured dimensions: the key
    poses first, then the return points, then ``TURN_SAMPLES`` turns over the whole turn."""
    problem = result.problem
    returns = result.design.stroke.carrier_turns
    turns = np.r_[problem.carrier_turns, returns, np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)]
    rows = gear_rows(result.design.relative_angle, result.toothed.train, turns)
    at_turn, sampled = backend_motion("fivebar_built_motion", built_motion, result, DIMENSION_NAMES, rows)
    return ToleranceModel(problem.title or problem.source, _dimensions(result), at_turn, rows,
                          sampled, np.degrees(turns), problem.labels,
                          slice(len(turns) - TURN_SAMPLES, None),
                          HardConditions(result, len(problem.carrier_turns), len(returns)))

"""A built four-gear planetary train (sun, two intermediates on one shaft, planet) as a function of its
manufactured dimensions: the planet's turn against the carrier, for the five-bar and the reverse train.

Seen in the carrier's frame (angles in the sense the sun turns against the carrier), the carrier's axis runs
from O to the planet's shaft A; the intermediate shaft sits at a1 from O, turned by ``bend`` from that axis.
The sun, fixed to the frame, stands at c + phase_sun against the carrier; stage 1 turns the intermediate
shaft by psi, seen along the line of centres O->shaft (which the bend's error turns); stage 2 turns the planet
by chi, seen along the line shaft->A. Each stage's driven gear lags its designed motion by its lost motion
plus the backlash a larger centre distance opens, delta a tan(alpha) / r (r the driven gear's pitch radius at
the contact), taken up against the load, which resists the motion. psi and chi enter as their second-order
expansion about the designed motion at each c (the next term moves a tip by about 1e-6 mm at a 0.1 deg phase).

Dimensions (deg): ``backlash_stage_1`` / ``_2``, the driven gear's lost motion within half the ISO/TR 10064-2
minimum normal backlash 2/3 (0.06 + 0.0005 a + 0.03 m) mm over cos(alpha) times the driven gear's mean pitch
radius; ``phase_<gear>``, each gear's assembly phase on its shaft, +-``PHASE_DEG``.
"""
from __future__ import annotations

import numpy as np

from transplanter.geometry.planar import TWO_PI
from transplanter.tolerance.dimensions import Dimension

#: Assembly phase of each gear on its shaft (deg).
PHASE_DEG = 0.1
#: Carrier turns the default backlash is averaged over.
BACKLASH_GRID = np.linspace(0, TWO_PI, 120, endpoint=False)
GEARS = ("sun", "first_intermediate", "second_intermediate", "planet")
GEAR_DIMENSION_NAMES = ("backlash_stage_1", "backlash_stage_2", *(f"phase_{gear}" for gear in GEARS))


def minimum_backlash_mm(center_distance: float, module: float) -> float:
    """ISO/TR 10064-2's minimum normal backlash (mm) for a centre distance and module (mm)."""
    return 2 / 3 * (0.06 + 0.0005 * center_distance + 0.03 * module)


def gear_rows(relative, train, c: np.ndarray) -> np.ndarray:
    """Per carrier turn: c, chi(c), psi', psi'' (against c), chi' and chi'' against psi, and the driven gears'
    pitch radii at their contact (mm); (8, T). ``relative`` gives chi(c) and its derivatives, ``train`` is the
    ``PlanetaryTrain`` that makes it."""
    k, p = train.correction, train.exponent
    s1, s2 = relative.evaluate(c, 1), relative.evaluate(c, 2)
    psi_1, psi_2 = k * s1**p, k * p * s1 ** (p - 1) * s2
    chi_1, chi_2 = s1 / psi_1, (s2 * psi_1 - s1 * psi_2) / psi_1**3
    a1, a2 = train.center_distances
    first = a1 - train.sun.evaluate(np.mod(c, TWO_PI))[0]
    planet = a2 - train.second_intermediate.evaluate(train.intermediate_turn(np.mod(c, TWO_PI)))[0]
    chi = relative.evaluate(c) - relative.evaluate(np.zeros(1))[0]
    return np.vstack([c, chi, psi_1, psi_2, chi_1, chi_2, first, planet])


def gear_dimensions(rows: np.ndarray, center_distances: tuple[float, float], module: float, pressure_angle: float,
                    gears: tuple[str, ...] = GEARS) -> list[Dimension]:
    """The backlash and phase dimensions (with their defaults) of a train whose ``gear_rows`` over an even grid
    of the turn are ``rows``, at ``center_distances`` (mm), ``module`` (mm) and ``pressure_angle`` (rad); a phase
    for each of ``gears``."""
    backlash = [Dimension(f"backlash_stage_{j + 1}", 0.0,
                          float(np.degrees(minimum_backlash_mm(a, module) / 2
                                           / (np.cos(pressure_angle) * rows[6 + j].mean()))),
                          "deg", "half the minimum backlash") for j, a in enumerate(center_distances)]
    return [*backlash, *(Dimension(f"phase_{gear}", 0.0, PHASE_DEG, "deg", "assembly phase") for gear in gears)]


def planet_turn(lib, g, center_distances: tuple[float, float], pressure_angle: float, nominal: tuple[float, float],
                carrier: tuple, v: dict):
    """The planet's turn against the carrier's axis (rad) of the built train, on a backend ``lib``: ``g`` the
    ``gear_rows`` of the turns, ``center_distances`` the designed a1, a2 (mm), ``nominal`` the designed (carrier
    length OA (mm), bend (rad)), ``carrier`` the built (OA, a1 (mm), bend (deg)), ``v`` the
    ``GEAR_DIMENSION_NAMES`` by name (deg; a train with one gear on the intermediate shaft, an idler, has no
    intermediate phases: its phase against itself is nil)."""
    rad = np.pi / 180
    _, chi0, psi_1, psi_2, chi_1, chi_2, r_first, r_planet = g
    a1_0, a2_0 = center_distances
    length_0, bend_0 = nominal
    length, a1, bend = carrier
    shaft_x, shaft_y = a1 * lib.cos(bend * rad), a1 * lib.sin(bend * rad)
    to_a_x, to_a_y = length - shaft_x, -shaft_y
    line_1 = bend * rad - bend_0
    line_2 = lib.atan2(to_a_y, to_a_x) - np.arctan2(-a1_0 * np.sin(bend_0), length_0 - a1_0 * np.cos(bend_0))
    tan_alpha = np.tan(pressure_angle)
    lag_1 = v["backlash_stage_1"] * rad + (a1 - a1_0) * tan_alpha / r_first
    lag_2 = v["backlash_stage_2"] * rad + (lib.sqrt(to_a_x**2 + to_a_y**2) - a2_0) * tan_alpha / r_planet
    sun_off = v["phase_sun"] * rad - line_1
    psi_off = (line_2 - line_1 + psi_1 * sun_off + psi_2 * sun_off**2 / 2 - lag_1
               + (v.get("phase_first_intermediate", 0.0) - v.get("phase_second_intermediate", 0.0)) * rad)
    chi = chi0 + chi_1 * psi_off + chi_2 * psi_off**2 / 2
    return line_2 + chi - lag_2 + v["phase_planet"] * rad

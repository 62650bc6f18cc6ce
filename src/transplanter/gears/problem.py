"""TOML gear-pair files (mm, degrees) -> a validated ``GearProblem``.

    title = "..."
    [driver]
    family = "ellipse"            # ellipse, higher_order_ellipse, denatured_ellipse, limacon,
                                  # denatured_limacon, spline, ratio
    semi_major_axis = 30.0        # ellipse families: r = a (1 - e^2) / (1 - e cos(n phi))
    eccentricity = 0.3
    order = 1                     # n1: lobes of the driver (ellipse 1; higher-order ellipse, limacon >= 1)
    base = 53.0                   # limacon families: r = base + amplitude cos(order phi)
    amplitude = 13.0
    m11 = 1.5                     # denatured families (the onion-transplanter paper eq 2-3); m12 defaults to 1 / (2 - 1/m11)
    phi_deg = [...]               # spline: samples of the radius; ratio: samples of i12 = omega1/omega2
    radius = [...]                # spline (mm)
    ratio = [...]                 # ratio: samples of i12 (with phi_deg) ...
    expression = "1 + 0.3*cos(phi)"   # ... or a formula of phi (radians): + - * / **, cos sin tan exp sqrt log, pi
    correct = false               # ratio: scale i12 so that the pair closes (Wang et al. 2025 eq 12)
    [pair]
    driven_order = 1              # n2: the driven gear turns n1/n2 per driver turn
    center_distance = 60.0        # optional: solved for closure when absent (required for ratio)
    module = 2.0                  # optional: tooth counts, and tooth profiles
    teeth = 30                    # optional: driver teeth; the curve is scaled so its perimeter is pi m Z
    pressure_angle_deg = 20.0
    driver_speed_rpm = 60.0
    cutter = "rack"               # "rack" or "shaper" for the tooth profiles
    shaper_teeth = 16             # shaper cutter teeth
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import casadi as ca
import numpy as np

from transplanter.gears.pitch_curves import (PitchCurve, denatured_ellipse, denatured_limacon, denatured_partner, ellipse,
                                       limacon, ratio_formula, ratio_samples, spline)
from transplanter.gears.ratio_expression import ExpressionError, parse_ratio
from transplanter.toml_fields import ClassFields, FieldReader, is_finite_number, read_toml, shown

FAMILIES = ("ellipse", "higher_order_ellipse", "denatured_ellipse", "limacon", "denatured_limacon", "spline", "ratio")
_DRIVER_KEYS = {"family", "semi_major_axis", "eccentricity", "order", "base", "amplitude", "m11", "m12",
                "phi_deg", "radius", "ratio", "expression", "correct"}
_FAMILY_KEYS = {
    "ellipse": {"semi_major_axis", "eccentricity", "order"},
    "higher_order_ellipse": {"semi_major_axis", "eccentricity", "order"},
    "denatured_ellipse": {"semi_major_axis", "eccentricity", "m11", "m12"},
    "limacon": {"base", "amplitude", "order"},
    "denatured_limacon": {"base", "amplitude", "m11", "m12"},
    "spline": {"phi_deg", "radius"},
    "ratio": {"phi_deg", "ratio", "expression", "correct"},
}
_PAIR_KEYS = {"driven_order", "center_distance", "module", "teeth", "pressure_angle_deg", "driver_speed_rpm",
              "cutter", "shaper_teeth"}


@dataclass(frozen=True)
class GearProblem:
    """A validated gear-pair problem, in mm, radians and rad/s (``parse_problem`` takes degrees and rpm).

    Attributes
    ----------
    driver : PitchCurve or None
        The driver's pitch curve; None for a ratio input (built once the center distance is known).
    driven_order : int
        n2: the driven gear turns n1/n2 per driver turn.
    center_distance : float or None
        mm; None: solved for closure.
    module : float or None
        mm, for tooth counts and profiles.
    teeth : int or None
        Driver teeth: the curve is scaled so its perimeter is pi m Z.
    pressure_angle : float
        rad, from 5 to 35 degrees.
    driver_speed : float
        rad/s.
    cutter : str
        ``"rack"`` or ``"shaper"``.
    shaper_teeth : int
        Teeth of the shaper cutter.
    source, title : str
        Where the problem came from and its title.
    ratio : tuple or None
        (evaluator of i12 and its derivatives, breaks in rad) for a ratio input.
    correct_ratio : bool
        Scale a ratio that does not close (Wang et al. 2025 eq 12).
    parameters : dict
        The driver's parameters as given, for the report.

    Raises
    ------
    ProblemError
        When a value is out of range, e.g. a pressure angle given in degrees.
    """

    driver: PitchCurve | None
    driven_order: int
    center_distance: float | None
    module: float | None
    teeth: int | None
    pressure_angle: float
    driver_speed: float
    cutter: str
    shaper_teeth: int
    source: str
    title: str = ""
    ratio: tuple | None = None
    correct_ratio: bool = False
    parameters: dict = field(default_factory=dict)

    def __post_init__(self):
        check = ClassFields(self)
        if (self.driver is None) == (self.ratio is None):
            check.fail("driver", self.driver, "a pitch curve, or None with a ratio")
        if not np.radians(5) - 1e-12 <= self.pressure_angle <= np.radians(35) + 1e-12:
            check.fail("pressure_angle", self.pressure_angle, "an angle from 5 to 35 degrees, in radians")
        if not is_finite_number(self.driver_speed):
            check.fail("driver_speed", self.driver_speed, "a finite speed (rad/s)")
        for name in ("center_distance", "module"):
            check.positive(name, optional=True)
        if self.cutter not in ("rack", "shaper"):
            check.fail("cutter", self.cutter, '"rack" or "shaper"')


def load_problem(path: str | Path) -> GearProblem:
    """Read and validate a gear-pair file (TOML, mm and degrees; schema above).

    Raises
    ------
    ProblemError
        Naming the file, the field, the value and what was expected.
    """
    return parse_problem(read_toml(path), str(path))


def _positive(read, table, key, where):
    value = read.number(table, key, where)
    if value <= 0:
        read.fail(f"{where}.{key}", value, "a positive number")
    return value


def _eccentricity(read, table):
    e = read.number(table, "eccentricity", "driver")
    if not 0 <= e < 1:
        read.fail("driver.eccentricity", e, "a number in [0, 1)")
    return e


def _denatured_pair(read, table):
    m11 = read.number(table, "m11", "driver")
    if m11 <= 0.5:
        read.fail("driver.m11", m11, "more than 1/2 (the onion-transplanter paper eq 2)")
    m12 = denatured_partner(m11)
    if "m12" in table:
        given = read.number(table, "m12", "driver")
        if abs(given - m12) > 1e-9 * m12:
            read.fail("driver.m12", given, f"{m12:.12g}, from pi/m11 + pi/m12 = 2 pi (the onion-transplanter paper eq 2); "
                                           f"with {given:g} the pitch curve breaks at phi = {180 / m11:.6g} deg")
    return m11, m12


def _driver(read: FieldReader, table: dict):
    read.keys(table, _DRIVER_KEYS, "driver")
    family = table.get("family")
    if family not in FAMILIES:
        read.fail("driver.family", family, "one of " + ", ".join(FAMILIES))
    read.keys(table, _FAMILY_KEYS[family] | {"family"}, "driver")
    if family in ("ellipse", "higher_order_ellipse"):
        low = 1 if family == "ellipse" else 2
        order = read.integer(table, "order", "driver", low, 1 if family == "ellipse" else 12, default=low)
        return ellipse(_positive(read, table, "semi_major_axis", "driver"), _eccentricity(read, table), order)
    if family == "limacon":
        return limacon(_positive(read, table, "base", "driver"), read.number(table, "amplitude", "driver"),
                       read.integer(table, "order", "driver", 1, 12, default=1))
    if family == "denatured_ellipse":
        return denatured_ellipse(_positive(read, table, "semi_major_axis", "driver"), _eccentricity(read, table),
                                 *_denatured_pair(read, table))
    if family == "denatured_limacon":
        return denatured_limacon(_positive(read, table, "base", "driver"), read.number(table, "amplitude", "driver"),
                                 *_denatured_pair(read, table))
    if family == "ratio" and "expression" in table:
        if "ratio" in table or "phi_deg" in table:
            read.fail("driver.expression", table["expression"], "either an expression or phi_deg and ratio, not both")
        text = table["expression"]
        phi = ca.SX.sym("phi")
        try:
            return ratio_formula(parse_ratio(str(text), phi), phi), ()
        except ExpressionError as error:
            read.fail("driver.expression", text, f"a formula of phi: {error}")
    phi = np.radians(read.numbers(table, "phi_deg", "driver", minimum_count=4))
    key = "radius" if family == "spline" else "ratio"
    values = read.numbers(table, key, "driver", minimum_count=4)
    if len(values) != len(phi):
        read.fail(f"driver.{key}", f"{len(values)} values", f"one per driver.phi_deg ({len(phi)})")
    wrapped = np.mod(phi, 2 * np.pi)
    if len(np.unique(np.round(wrapped, 12))) != len(wrapped):
        read.fail("driver.phi_deg", table["phi_deg"], "distinct angles within one turn")
    if values.min() <= 0:
        read.fail(f"driver.{key}", float(values.min()), "positive values all round"
                  + (" (a ratio that touches zero or goes negative reverses the driven gear)" if key == "ratio" else ""))
    if family == "spline":
        return spline(phi, values)
    return ratio_samples(phi, values), tuple(np.mod(phi, 2 * np.pi))


def parse_problem(data: dict, source: str = "<dict>") -> GearProblem:
    """Validate a gear-pair problem given as a dict with the fields of the file (mm, degrees, rpm).

    Parameters
    ----------
    data : dict
        The file's tables as dicts; a list of numbers may be a tuple or a numpy array.
    source : str
        Named in error messages (the file name when read from a file).

    Returns
    -------
    GearProblem
        In mm, radians and rad/s.

    Raises
    ------
    ProblemError
        Naming the source, the field, the value and what was expected.
    """
    read = FieldReader(source)
    read.keys(data, {"title", "description", "driver", "pair"}, "")
    if "driver" not in data:
        read.fail("driver", None, "a table [driver] with a family")
    driver = _driver(read, data["driver"])
    pair = data.get("pair", {})
    read.keys(pair, _PAIR_KEYS, "pair")
    center = _positive(read, pair, "center_distance", "pair") if "center_distance" in pair else None
    module = _positive(read, pair, "module", "pair") if "module" in pair else None
    teeth = read.integer(pair, "teeth", "pair", 3, 100000) if "teeth" in pair else None
    if teeth is not None and module is None:
        read.fail("pair.teeth", teeth, "a module as well (pair.module), since teeth scale the curve to pi m Z")
    if teeth is not None and center is not None:
        read.fail("pair.center_distance", center, "no center distance when pair.teeth is given (scaling sets it)")
    pressure = read.number(pair, "pressure_angle_deg", "pair") if "pressure_angle_deg" in pair else 20.0
    if not 5 <= pressure <= 35:
        read.fail("pair.pressure_angle_deg", pressure, "an angle from 5 to 35 degrees")
    rpm = read.number(pair, "driver_speed_rpm", "pair") if "driver_speed_rpm" in pair else 60.0
    cutter = pair.get("cutter", "rack")
    if cutter not in ("rack", "shaper"):
        read.fail("pair.cutter", cutter, '"rack" or "shaper"')
    is_ratio = isinstance(driver, tuple)
    if is_ratio and center is None and teeth is None:
        read.fail("pair.center_distance", None, "a center distance (or module and teeth): a ratio fixes the "
                                                "shape of the pitch curves, not their size")
    correct = read.flag(data["driver"], "correct", "driver", False)
    return GearProblem(
        driver=None if is_ratio else driver,
        driven_order=read.integer(pair, "driven_order", "pair", 1, 12, default=1),
        center_distance=center, module=module, teeth=teeth, pressure_angle=float(np.radians(pressure)),
        driver_speed=rpm * 2 * np.pi / 60, cutter=cutter,
        shaper_teeth=read.integer(pair, "shaper_teeth", "pair", 8, 200, default=16),
        source=source, title=str(data.get("title", "")), ratio=driver if is_ratio else None,
        correct_ratio=correct, parameters={k: shown(v) for k, v in data["driver"].items()
                                           if k not in ("family", "phi_deg", "radius", "ratio", "expression")})

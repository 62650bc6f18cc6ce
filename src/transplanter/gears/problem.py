"""TOML gear-pair files (mm, degrees) -> a validated ``GearProblem``.

    title = "..."
    [driver]
    family = "ellipse"            # ellipse, higher_order_ellipse, denatured_ellipse, limacon,
                                  # denatured_limacon, spline, ratio, composite
    [[driver.segments]]           # composite: segments round the turn (composite_fields.py, docs/gear.md)
    semi_major_axis = 30.0        # ellipse families: r = a (1 - e^2) / (1 - e cos(n phi))
    eccentricity = 0.3
    order = 1                     # n1: lobes of the driver (ellipse 1; higher-order ellipse, limacon >= 1)
    base = 53.0                   # limacon families: r = base + amplitude cos(order phi)
    amplitude = 13.0
    m11 = 1.5                     # denatured families (the onion-transplanter paper eq 2-3);
                                  # m12 defaults to 1 / (2 - 1/m11)
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
    corner_pressure_angle_deg = 22.0   # composite: pressure angle of the contact as a corner passes; when
                                       # absent 22, 26, 30, 34, 38 are tried and the first pair that passes is kept
    face_width_mm = 20.0          # optional: the gears' STEP solids (solids/sizes.py; default 10 modules)
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import casadi as ca
import numpy as np

from transplanter.errors import ProblemError
from transplanter.gears.composite_fields import read_composite
from transplanter.gears.pitch_curves import (
    PitchCurve,
    denatured_ellipse,
    denatured_limacon,
    denatured_partner,
    ellipse,
    limacon,
    ratio_formula,
    ratio_samples,
    spline,
)
from transplanter.gears.ratio_expression import ExpressionError, parse_ratio
from transplanter.solids.sizes import SolidSizes, read_solid_sizes
from transplanter.toml_fields import LONGEST_TITLE, ClassFields, FieldReader, read_toml, shown

FAMILIES = ("ellipse", "higher_order_ellipse", "denatured_ellipse", "limacon", "denatured_limacon", "spline", "ratio",
            "composite")
_DRIVER_KEYS = {"family", "semi_major_axis", "eccentricity", "order", "base", "amplitude", "m11", "m12",
                "phi_deg", "radius", "ratio", "expression", "correct", "segments"}
_FAMILY_KEYS = {
    "ellipse": {"semi_major_axis", "eccentricity", "order"},
    "higher_order_ellipse": {"semi_major_axis", "eccentricity", "order"},
    "denatured_ellipse": {"semi_major_axis", "eccentricity", "m11", "m12"},
    "limacon": {"base", "amplitude", "order"},
    "denatured_limacon": {"base", "amplitude", "m11", "m12"},
    "spline": {"phi_deg", "radius"},
    "ratio": {"phi_deg", "ratio", "expression", "correct"},
    "composite": {"segments"},
}
#: Most samples of a spline radius or a sampled ratio (a sample every 0.018 deg): the pitch curves' work grows with
#: their number (20,000 samples of a ratio: 14 s and 0.46 GB; 100,000 past two minutes).
LARGEST_SAMPLE_COUNT = 20000
#: Transmission ratios i12 accepted, all round: beyond them one pitch radius is a thousandth of the other.
RATIO_RANGE = (1e-3, 1e3)
#: Most teeth cut on one gear: every tooth's envelope is cut and checked, with time and memory in
#: proportion (20000 teeth a gear: 10 s and 0.36 GB on the ellipse example).
MAX_TEETH = 20000
#: Most teeth on a composite driver: its mate is carved as polygons at every CARVE_STEP_MODULES of a turn, and the
#: carving's time and memory grow with the count squared (measured on the ellipse-and-chord example: 30 teeth 4 s,
#: 100 teeth 14 s, 200 teeth 1 min and 1.1 GB with every file written, 500 teeth over 5 min and 2.4 GB).
MAX_COMPOSITE_TEETH = 200
#: Most teeth on a shaper-cut gear: the cutter's envelope is taken at every position it rolls through, in time and
#: memory growing faster than the count (the concave example: 1000 teeth 51 s and 0.35 GB, 2000 teeth 134 s and
#: 1.2 GB, 20000 teeth over 5 min and 4.4 GB).
MAX_SHAPER_TEETH = 1000
_PAIR_KEYS = {"driven_order", "center_distance", "module", "teeth", "pressure_angle_deg", "driver_speed_rpm",
              "cutter", "shaper_teeth", "corner_pressure_angle_deg", "face_width_mm"}


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
    corner_pressure_angle : float or None
        Composite teeth: rad, the contact's pressure angle as a corner passes (theta_J / 2); None tries several.
    solid_sizes : SolidSizes
        The face width of the gears' STEP solids (mm; None: the rule of ``solids.sizes``).

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
    corner_pressure_angle: float | None = None
    solid_sizes: SolidSizes = field(default_factory=SolidSizes)

    def __post_init__(self):
        check = ClassFields(self)
        if (self.driver is None) == (self.ratio is None) or not isinstance(self.driver, (PitchCurve, type(None))):
            check.fail("driver", self.driver, "a pitch curve (gears.pitch_curves.PitchCurve), or None with a ratio")
        check.number("pressure_angle", np.radians(5) - 1e-12, np.radians(35) + 1e-12,
                     "an angle from 5 to 35 degrees, in radians")
        check.speed("driver_speed")
        check.whole("driven_order", 1, 12)
        check.whole("teeth", 1, MAX_TEETH, optional=True)
        check.whole("shaper_teeth", 8, 200)
        if self.teeth is not None and self.module is None:
            check.fail("teeth", self.teeth, "None without a module (teeth set the perimeter pi m Z)")
        for name in ("center_distance", "module"):
            check.positive(name, optional=True)
        check.choice("cutter", ("rack", "shaper"))
        check.text("source", "title")
        if not isinstance(self.solid_sizes, SolidSizes):
            check.fail("solid_sizes", self.solid_sizes, "a solids.sizes.SolidSizes")
        corner = self.corner_pressure_angle
        if corner is not None and not self.pressure_angle < corner < np.radians(80):
            check.fail("corner_pressure_angle", self.corner_pressure_angle,
                       "an angle (rad) above the pressure angle and below 80 degrees")


def ratio_defect(evaluate) -> str | None:
    """What is wrong with a transmission ratio i12 (``evaluate(phi)`` -> i12, its slope, ...) over a turn, or
    None: where it is not finite, or leaves ``RATIO_RANGE``, on a dense grid and between its samples
    (``_between_samples``: a pole narrower than the grid is found there)."""
    dense = np.linspace(0, 2 * np.pi, 20001)
    with np.errstate(all="ignore"):
        values, slopes = (np.asarray(v, float) for v in evaluate(dense)[:2])
    return _range_defect(dense, values) or _between_samples(evaluate, dense, values, slopes)


def _range_defect(phi: np.ndarray, values: np.ndarray) -> str | None:
    """Where the ratio samples ``values`` at ``phi`` are not finite or leave ``RATIO_RANGE``, or None."""
    finite = np.isfinite(values)
    low, high = RATIO_RANGE
    if finite.all() and low <= values.min() and values.max() <= high:
        return None
    if not finite.all():
        k, why = int(np.argmin(finite)), "expected a finite ratio all round"
    elif values.min() <= 0:
        k, why = int(np.argmin(values)), ("a ratio that touches zero or goes negative reverses the driven gear; "
                                          "expected a positive ratio all round")
    else:
        k = int(np.argmin(values)) if values.min() < low else int(np.argmax(values))
        why = (f"expected i12 from {low:g} to {high:g} all round: "
               "beyond it one pitch radius is a thousandth of the other")
    return f"reaches {values[k]:.6g} at phi = {np.degrees(phi[k]):.2f} deg: {why}"


#: Between two samples the ratio must be the cubic through their values and slopes to this fraction of its size,
#: else the stretch is halved until it is (a smooth ratio at 20001 samples misses by ~1e-16).
RESOLVED = 1e-6
#: Narrowest stretch halved to (rad): a ratio still unresolved there jumps, or has a pole too narrow for doubles.
NARROWEST = 1e-13


def _between_samples(evaluate, phi: np.ndarray, values: np.ndarray, slopes: np.ndarray) -> str | None:
    """Where the ratio, between samples that look well, leaves the range or cannot be resolved, or None.
    Each stretch whose midpoint misses the cubic Hermite through its ends by more than ``RESOLVED`` of the ratio's
    size is halved, down to ``NARROWEST``; the range is checked at every midpoint taken."""
    scale = max(1.0, float(np.max(np.abs(values))))
    left, width = phi[:-1], np.diff(phi)
    ends = (values[:-1], slopes[:-1], values[1:], slopes[1:])
    while True:
        middle = left + width / 2
        with np.errstate(all="ignore"):
            value, slope = (np.asarray(v, float) for v in evaluate(middle)[:2])
        defect = _range_defect(middle, value)
        if defect:
            return defect
        v0, s0, v1, s1 = ends
        miss = np.abs(value - ((v0 + v1) / 2 + width * (s0 - s1) / 8))
        unresolved = miss > RESOLVED * scale
        if not unresolved.any():
            return None
        if width[unresolved].min() < NARROWEST:
            k = int(np.argmax(np.where(unresolved, miss, -1.0)))
            return (f"is not resolved near phi = {np.degrees(middle[k]):.6f} deg: between values {width[k]:.2g} rad "
                    f"apart it is {miss[k]:.3g} off the cubic through them; expected a ratio smooth all round (a "
                    "pole or a jump is there)")
        left = np.concatenate([left[unresolved], middle[unresolved]])
        width = np.concatenate([width[unresolved]] * 2) / 2
        ends = (np.concatenate([v0[unresolved], value[unresolved]]),
                np.concatenate([s0[unresolved], slope[unresolved]]),
                np.concatenate([value[unresolved], v1[unresolved]]),
                np.concatenate([slope[unresolved], s1[unresolved]]))


def load_problem(path: str | Path) -> GearProblem:
    """Read and validate a gear-pair file (TOML, mm and degrees; schema above).

    Raises
    ------
    ProblemError
        Naming the file, the field, the value and what was expected.
    """
    return parse_problem(read_toml(path), str(path))


def _eccentricity(read, table, where="driver"):
    e = read.number(table, "eccentricity", where)
    if not 0 <= e < 1:
        read.fail(f"{where}.eccentricity", e, "a number in [0, 1)")
    return e


def _amplitude(read, table, where="driver"):
    """A limacon's amplitude: below its base, so the radius base - |amplitude| stays positive."""
    base, amplitude = table.get("base"), read.number(table, "amplitude", where)
    if abs(amplitude) >= base:
        read.fail(f"{where}.amplitude", amplitude, f"|amplitude| below {where}.base = {base:g} mm (the pitch radius "
                                                   f"base + amplitude cos reaches base - |amplitude| <= 0)")
    return amplitude


def _denatured_pair(read, table, where="driver"):
    m11 = read.number(table, "m11", where)
    if m11 <= 0.5:
        read.fail(f"{where}.m11", m11, "more than 1/2 (the onion-transplanter paper eq 2)")
    m12 = denatured_partner(m11)
    if "m12" in table:
        given = read.number(table, "m12", where)
        if abs(given - m12) > 1e-9 * m12:
            read.fail(f"{where}.m12", given, f"{m12:.12g}, from pi/m11 + pi/m12 = 2 pi "
                                           f"(the onion-transplanter paper eq 2); "
                                           f"with {given:g} the pitch curve breaks at phi = {180 / m11:.6g} deg")
    return m11, m12


def read_driver(read: FieldReader, table: dict, where: str = "driver", families=FAMILIES):
    """A driver pitch curve from its table (any family of ``families``); a ratio gives (evaluator, breaks)."""
    family = table.get("family") if isinstance(table, dict) else None
    if not isinstance(family, str) or family not in families:
        read.keys(table, _DRIVER_KEYS, where)
        read.fail(f"{where}.family", family, "one of " + ", ".join(families))
    read.keys(table, _FAMILY_KEYS[family] | {"family"}, where)
    if family == "composite":
        return read_composite(read, table, where, read_driver, _FAMILY_KEYS, LARGEST_SAMPLE_COUNT)
    if family in ("ellipse", "higher_order_ellipse"):
        low = 1 if family == "ellipse" else 2
        order = read.integer(table, "order", where, low, 1 if family == "ellipse" else 12, default=low)
        return ellipse(read.length(table, "semi_major_axis", where), _eccentricity(read, table, where), order)
    if family == "limacon":
        return limacon(read.length(table, "base", where), _amplitude(read, table, where),
                       read.integer(table, "order", where, 1, 12, default=1))
    if family == "denatured_ellipse":
        return denatured_ellipse(read.length(table, "semi_major_axis", where), _eccentricity(read, table, where),
                                 *_denatured_pair(read, table, where))
    if family == "denatured_limacon":
        return denatured_limacon(read.length(table, "base", where), _amplitude(read, table, where),
                                 *_denatured_pair(read, table, where))
    if family == "ratio" and "expression" in table:
        if "ratio" in table or "phi_deg" in table:
            read.fail(f"{where}.expression", table["expression"], "either an expression or phi_deg and ratio, not both")
        text = table["expression"]
        if not isinstance(text, str):
            read.fail(f"{where}.expression", text, f'a formula of phi as text, e.g. "{text}" for a constant ratio')
        phi = ca.SX.sym("phi")
        try:
            evaluate = ratio_formula(parse_ratio(text, phi), phi)
        except ExpressionError as error:
            read.fail(f"{where}.expression", text, f"a formula of phi: {error}")
        defect = ratio_defect(evaluate)
        if defect:
            raise ProblemError(f"{read.source}: {where}.expression = {shown(text)!r} {defect}")
        return evaluate, ()
    phi = np.radians(read.numbers(table, "phi_deg", where, minimum_count=4, largest=LARGEST_SAMPLE_COUNT))
    key = "radius" if family == "spline" else "ratio"
    values = read.numbers(table, key, where, minimum_count=4, largest=LARGEST_SAMPLE_COUNT)
    if len(values) != len(phi):
        read.fail(f"{where}.{key}", f"{len(values)} values", f"one per driver.phi_deg ({len(phi)})")
    wrapped = np.mod(phi, 2 * np.pi)
    if len(np.unique(np.round(wrapped, 12))) != len(wrapped):
        read.fail(f"{where}.phi_deg", table["phi_deg"], "distinct angles within one turn")
    if values.min() <= 0:
        why = " (a ratio that touches zero or goes negative reverses the driven gear)" if key == "ratio" else ""
        read.fail(f"{where}.{key}", float(values.min()), "positive values all round" + why)
    if family == "spline":
        return spline(phi, values)
    evaluate = ratio_samples(phi, values)
    defect = ratio_defect(evaluate)
    if defect:
        raise ProblemError(f"{read.source}: driver.ratio (the periodic spline through the samples) {defect}")
    return evaluate, tuple(np.mod(phi, 2 * np.pi))


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
    driver = read_driver(read, data["driver"])
    pair = data.get("pair", {})
    read.keys(pair, _PAIR_KEYS, "pair")
    center = read.length(pair, "center_distance", "pair") if "center_distance" in pair else None
    module = read.length(pair, "module", "pair") if "module" in pair else None
    teeth = read.integer(pair, "teeth", "pair", 3, MAX_TEETH) if "teeth" in pair else None
    if teeth is not None and module is None:
        read.fail("pair.teeth", teeth, "a module as well (pair.module), since teeth scale the curve to pi m Z")
    if teeth is not None and center is not None:
        read.fail("pair.center_distance", center, "no center distance when pair.teeth is given (scaling sets it)")
    pressure = read.number(pair, "pressure_angle_deg", "pair") if "pressure_angle_deg" in pair else 20.0
    if not 5 <= pressure <= 35:
        read.fail("pair.pressure_angle_deg", pressure, "an angle from 5 to 35 degrees")
    rpm = read.number(pair, "driver_speed_rpm", "pair") if "driver_speed_rpm" in pair else 60.0
    if rpm == 0:
        read.fail("pair.driver_speed_rpm", rpm, "a speed other than 0 (rpm)")
    cutter = pair.get("cutter", "rack")
    if cutter not in ("rack", "shaper"):
        read.fail("pair.cutter", cutter, '"rack" or "shaper"')
    if cutter == "shaper" and teeth is not None and teeth > MAX_SHAPER_TEETH:
        read.fail("pair.teeth", teeth, f'at most {MAX_SHAPER_TEETH} with cutter = "shaper" (its envelope is taken at '
                                       "every position the cutter rolls through)")
    composite = data["driver"].get("family") == "composite"
    if composite and teeth is not None and teeth > MAX_COMPOSITE_TEETH:
        read.fail("pair.teeth", teeth, f'at most {MAX_COMPOSITE_TEETH} with family = "composite" (the mate is carved '
                                       "as polygons, in time and memory growing with the count squared)")
    if composite and pair.get("cutter") == "rack":
        read.fail("pair.cutter", cutter, 'no cutter or "shaper" with family = "composite": a rack cannot roll round '
                                         "a corner, so the smooth stretches are shaper-cut")
    is_ratio = isinstance(driver, tuple)
    if is_ratio and center is None and teeth is None:
        read.fail("pair.center_distance", None, "a center distance (or module and teeth): a ratio fixes the "
                                                "shape of the pitch curves, not their size")
    correct = read.flag(data["driver"], "correct", "driver", False)
    corner = read.number(pair, "corner_pressure_angle_deg", "pair") if "corner_pressure_angle_deg" in pair else None
    if corner is not None and not composite:
        read.fail("pair.corner_pressure_angle_deg", corner, 'no such field for a pitch curve without corners: it '
                                                             'applies to family = "composite"')
    if corner is not None and not pressure < corner < 80:
        read.fail("pair.corner_pressure_angle_deg", corner, f"an angle above pair.pressure_angle_deg ({pressure:g}) "
                                                             "and below 80 degrees (at 90 no torque passes the corner)")
    return GearProblem(
        driver=None if is_ratio else driver,
        driven_order=read.integer(pair, "driven_order", "pair", 1, 12, default=1),
        center_distance=center, module=module, teeth=teeth, pressure_angle=float(np.radians(pressure)),
        driver_speed=rpm * 2 * np.pi / 60, cutter=cutter,
        shaper_teeth=read.integer(pair, "shaper_teeth", "pair", 8, 200, default=16),
        source=source, title=read.text(data, "title", "", LONGEST_TITLE), ratio=driver if is_ratio else None,
        correct_ratio=correct, parameters={k: shown(v) for k, v in data["driver"].items()
                                           if k not in ("family", "phi_deg", "radius", "ratio", "expression")},
        corner_pressure_angle=None if corner is None else float(np.radians(corner)),
        solid_sizes=read_solid_sizes(read, pair, "pair"))

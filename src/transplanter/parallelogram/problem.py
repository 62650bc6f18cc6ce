"""TOML problem files of the onion transplanter (mm, degrees) -> a validated ``ParallelogramProblem``.

Schema (docs/parallelogram.md, "Problem files"); the driver gear's center O1 is the origin:

    title = "..."
    [design]                      # the onion-transplanter paper's eight variables (start values; fixed unless bounded)
    m11 = 1.5                     # denaturation coefficient of the first half (eq 2-3); m12 from eq (2)
    b = 13.0                      # limacon amplitude (mm), eq (1)
    l = 53.0                      # limacon base (mm)
    l1 = 82.0                     # crank O2A = DB (mm)
    l2 = 254.0                    # coupler AB = O2D (mm): only translates the path
    l5 = 61.0                     # BC (mm): only translates the path
    l6 = 119.0                    # CE, height of the duckbill (mm): only translates the path
    alpha_deg = 6.0               # initial phase of the crank (see [conventions])
    [gear]
    module = 2.0                  # mm: undercut check (rack, m / sin^2 of the pressure angle), tooth count
    pressure_angle_deg = 20.0
    face_width_mm = 20.0          # optional: the gears' STEP solids (solids/sizes.py; default 10 modules)
    [machine]
    driver_speed_rpm = 60.0       # constant speed of the driver gear
    forward_speed_mm_s = 300.0    # machine speed over the field (> 0)
    forward = "-x"                # direction the machine travels: "+x" or "-x"
    crank_pivot_mm = [0.0, 0.0]   # O2 relative to the driven gear's center O = (a, 0) (eq 16)
    [conventions]
    crank_sense = "counterclockwise"  # sense of the crank (and the driven gear) as phi2 grows
    alpha_reference_deg = -90.0   # crank direction (counterclockwise from +x) at the reference instant when alpha = 0
    alpha_instant = "slowest"     # reference instant: "slowest" (phi1 = pi/m11, smallest r1) or "driver_zero"
    [objectives]
    depth_window_mm = 0.5         # |X_E - X_E(t_E)| <= this defines the planting depth H (section 3.1.1)
    depth_target_mm = 25.0        # f2 = |H - target|
    depth_band_mm = [25.0, 30.0]  # constraint on H
    vertical_range_target_mm = 160.0   # f3 = |Y - target| (the printed f3 is garbled)
    [search]                      # NSGA-II (pymoo)
    population = 100
    generations = 100
    seed = 1
    [search.bounds]               # [low, high] of the searched variables: m11, b, l, l1, alpha_deg
    [printed]                     # optional: m12, center_distance, teeth as a paper prints them for [design]
    [published]                   # optional: depth_mm, vx_release_mm_s, vertical_range_mm, spacing_mm reported
    [tolerances]                  # optional: the built mechanism's tolerances (docs/tolerance.md)

The crank angle (counterclockwise from +x) is theta(phi1) = reference + sense (phi2(phi1) - phi2(phi1_ref) - alpha):
alpha is how far the crank lags, in its own sense, behind the reference direction at the reference instant.
Eq (17) as printed is reference 0 deg, instant "driver_zero", sense counterclockwise.
"""
from __future__ import annotations

import numbers
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from transplanter.errors import ProblemError
from transplanter.solids.sizes import SolidSizes, read_solid_sizes
from transplanter.tolerance.dimensions import ToleranceSettings, parse_tolerances
from transplanter.toml_fields import (
    LONGEST_TITLE,
    MAGNITUDE_LIMIT,
    ClassFields,
    FieldReader,
    is_finite_number,
    is_sequence,
    read_toml,
)

#: The eight design variables of the onion-transplanter paper in file order (mm; alpha in degrees in files,
#: radians inside).
VARIABLES = ("m11", "b", "l", "l1", "l2", "l5", "l6", "alpha")
#: Variables that only translate the path (zero derivatives of every objective): never searched.
TRANSLATION_ONLY = ("l2", "l5", "l6")
SEARCHABLE = ("m11", "b", "l", "l1", "alpha")
FILE_NAMES = {name: ("alpha_deg" if name == "alpha" else name) for name in VARIABLES}
INSTANTS = ("slowest", "driver_zero")
SENSES = {"counterclockwise": 1.0, "clockwise": -1.0}
DIRECTIONS = {"+x": 1.0, "-x": -1.0}
PUBLISHED_FIELDS = ("depth_mm", "vx_release_mm_s", "vertical_range_mm", "spacing_mm")
_TOP_KEYS = {"title", "description", "design", "gear", "machine", "conventions", "objectives", "search", "printed",
             "published", "tolerances"}

#: Most NSGA-II evaluations (population x generations) one search may ask for.
MAX_EVALUATIONS = 1_000_000
#: Largest NSGA-II population: pymoo's non-dominated sorting holds a domination matrix of the population and its
#: offspring, n x n, so memory grows with its square (measured peaks: 2500 0.24 GB, 5000 0.51 GB, 10000 1.8 GB).
LARGEST_POPULATION = 5000


@dataclass(frozen=True)
class Conventions:
    """How the mechanism is phased and moves (everything the paper leaves implicit).

    Attributes
    ----------
    crank_sense : float
        +1 when the crank turns counterclockwise as phi2 grows, -1 clockwise.
    alpha_reference : float
        rad, crank direction (counterclockwise from +x) at the reference instant when alpha = 0.
    alpha_instant : str
        ``"slowest"`` (phi1 = pi/m11, where r1 is smallest and the crank slowest) or ``"driver_zero"``.
    forward : float
        +1 when the machine travels along +x, -1 along -x.
    """

    crank_sense: float = 1.0
    alpha_reference: float = float(np.radians(-90.0))
    alpha_instant: str = "slowest"
    forward: float = -1.0


#: Eq (16)-(17) read literally: crank angle phi2 - alpha from +x, counted from phi1 = 0.
PRINTED_EQ17 = Conventions(crank_sense=1.0, alpha_reference=0.0, alpha_instant="driver_zero", forward=-1.0)


@dataclass(frozen=True)
class ParallelogramProblem:
    """A validated onion-transplanter problem (mm, radians, seconds).

    Attributes
    ----------
    design : dict
        The eight variables (``VARIABLES``; alpha in rad): start values, and the fixed ones.
    module, pressure_angle : float
        Gear module (mm) and pressure angle (rad) for the undercut check and tooth counts.
    driver_speed : float
        omega1 (rad/s, > 0).
    forward_speed : float
        Machine speed (mm/s, > 0).
    crank_pivot : ndarray, shape (2,)
        O2 relative to the driven gear's center (mm).
    conventions : Conventions
    depth_window, depth_target : float
        mm (section 3.1.1).
    depth_band : tuple of float
        mm, [low, high] constraint on H.
    vertical_range_target : float
        mm, target of Y in f3.
    bounds : dict
        Searched variable -> (low, high) (alpha in rad).
    population, generations, seed : int
        NSGA-II settings.
    printed, published : dict
        Optional: the gear values the paper printed for [design] (m12, center_distance, teeth) and the
        figures it reports (``PUBLISHED_FIELDS``), evaluated beside the search.
    tolerances : ToleranceSettings
        The ``[tolerances]`` table: tolerances of the built mechanism's dimensions
        (``parallelogram.tolerance_model``) and the analysis settings (``tolerance.dimensions``).
    solid_sizes : SolidSizes
        The face width of the gears' STEP solids (``[gear]``, mm; None: the rule of ``solids.sizes``).
    """

    design: dict
    module: float = 2.0
    pressure_angle: float = float(np.radians(20.0))
    driver_speed: float = 2 * np.pi
    forward_speed: float = 300.0
    crank_pivot: np.ndarray = field(default_factory=lambda: np.zeros(2))
    conventions: Conventions = Conventions()
    depth_window: float = 0.5
    depth_target: float = 25.0
    depth_band: tuple[float, float] = (25.0, 30.0)
    vertical_range_target: float = 160.0
    bounds: dict = field(default_factory=dict)
    population: int = 100
    generations: int = 100
    seed: int = 1
    source: str = "<dict>"
    title: str = ""
    printed: dict = field(default_factory=dict)
    published: dict = field(default_factory=dict)
    tolerances: ToleranceSettings = field(default_factory=ToleranceSettings)
    solid_sizes: SolidSizes = field(default_factory=SolidSizes)

    def __post_init__(self):
        check = ClassFields(self)
        check_design(check, self.design)
        for name in ("module", "forward_speed", "depth_window", "depth_target", "vertical_range_target"):
            check.positive(name)
        check.number("pressure_angle", np.radians(5), np.radians(35), "an angle from 5 to 35 degrees, in radians")
        check.number("driver_speed", 1e-9, MAGNITUDE_LIMIT, "a positive speed omega1 (rad/s)")
        check.array("crank_pivot", (2,))
        if not isinstance(self.conventions, Conventions):
            check.fail("conventions", self.conventions, "a Conventions")
        if not isinstance(self.solid_sizes, SolidSizes):
            check.fail("solid_sizes", self.solid_sizes, "a solids.sizes.SolidSizes")
        c = self.conventions
        for name, value, expected in (("crank_sense", c.crank_sense, (1.0, -1.0)), ("forward", c.forward, (1.0, -1.0)),
                                      ("alpha_instant", c.alpha_instant, ("slowest", "driver_zero"))):
            if not isinstance(value, (str, numbers.Real)) or isinstance(value, bool) or value not in expected:
                check.fail(f"conventions.{name}", value, "one of " + ", ".join(map(repr, expected)))
        if not is_finite_number(c.alpha_reference) or abs(c.alpha_reference) > 2 * np.pi:
            check.fail("conventions.alpha_reference", c.alpha_reference, "an angle within one turn of zero (rad)")
        band = np.asarray(self.depth_band, float) if is_sequence(self.depth_band) else None
        if band is None or band.shape != (2,) or not np.all(np.isfinite(band)) or not 0 <= band[0] < band[1]:
            check.fail("depth_band", self.depth_band, "(low, high) in mm with 0 <= low < high")
        if not isinstance(self.bounds, dict) or any(key not in SEARCHABLE for key in self.bounds):
            check.fail("bounds", self.bounds, f"a dict of (low, high) for some of {', '.join(SEARCHABLE)}")
        for key, pair in self.bounds.items():
            values = np.asarray(pair, float) if is_sequence(pair) else None
            if values is None or values.shape != (2,) or not np.all(np.isfinite(values)) or not values[0] < values[1] \
                    or (key == "alpha" and np.abs(values).max() > 2 * np.pi):
                check.fail(f"bounds[{key!r}]", pair, "(low, high) with low < high" + (" within one turn (rad)"
                                                                                       if key == "alpha" else ""))
        check.whole("population", 4, LARGEST_POPULATION)
        check.whole("generations", 1, MAX_EVALUATIONS)
        check.whole("seed", 0, 2**32 - 1)
        if self.population * self.generations > MAX_EVALUATIONS:
            check.fail("generations", self.generations, f"at most {MAX_EVALUATIONS:.0e} evaluations in all")
        check_gear_figures(check, self.printed, self.published)
        check.text("source", "title")

    @property
    def forward_velocity(self) -> float:
        """Signed machine velocity along x (mm/s)."""
        return self.conventions.forward * self.forward_speed

    @property
    def period(self) -> float:
        """One driver turn (s): one crank turn, so one plant."""
        return 2 * np.pi / self.driver_speed


def load_problem(path: str | Path) -> ParallelogramProblem:
    """The problem in the TOML file at ``path`` (see the module docstring)."""
    return parse_problem(read_toml(path), str(path))


def read_design(read: FieldReader, table, where: str = "design") -> dict:
    """The eight variables of a [design] table (alpha to radians), each checked."""
    read.keys(table, set(FILE_NAMES.values()), where)
    design = {}
    for name, key in FILE_NAMES.items():
        value = read.number(table, key, where)
        if name == "alpha":
            value = float(np.radians(value))
        elif value <= 0:
            read.fail(f"{where}.{key}", value, "a positive number" + (" (mm)" if name != "m11" else ""))
        design[name] = value
    if design["m11"] <= 0.5:
        read.fail(f"{where}.m11", design["m11"], "more than 0.5 (eq 2: m12 = 1 / (2 - 1/m11) must be positive)")
    if design["b"] >= design["l"]:
        read.fail(f"{where}.b", design["b"],
                  f"less than l = {design['l']:g} mm (the driver radius l - b must stay positive)")
    return design


def check_design(check: ClassFields, design):
    """A class's ``design``: the eight variables (``VARIABLES``), finite, lengths positive (mm), alpha within
    a turn (rad), m11 > 0.5 and b < l (as ``read_design`` holds the file's)."""
    if not isinstance(design, dict) or set(design) != set(VARIABLES):
        check.fail("design", design, f"a dict of exactly {', '.join(VARIABLES)} (mm; alpha in rad)")
    for name, value in design.items():
        if not is_finite_number(value) or (abs(value) > 2 * np.pi if name == "alpha" else value <= 0):
            check.fail(f"design[{name!r}]", value, "an angle within one turn (rad)" if name == "alpha" else
                       "a positive number" + (" (mm)" if name != "m11" else ""))
    if design["m11"] <= 0.5 or design["b"] >= design["l"]:
        check.fail("design", design, "m11 > 0.5 (eq 2) and b < l (the driver radius l - b stays positive)")


def check_gear_figures(check: ClassFields, printed, published):
    """A class's ``printed`` (m12, center_distance positive; teeth whole) and ``published`` (finite figures)."""
    if not isinstance(printed, dict) or set(printed) - {"m12", "center_distance", "teeth"}:
        check.fail("printed", printed, "a dict of some of m12, center_distance (mm), teeth")
    for key, value in printed.items():
        whole = key != "teeth" or isinstance(value, numbers.Integral)
        if not is_finite_number(value) or value <= 0 or not whole:
            check.fail(f"printed[{key!r}]", value, "a positive number" + (", whole" if key == "teeth" else ""))
    if not isinstance(published, dict) or set(published) - set(PUBLISHED_FIELDS) or \
            not all(is_finite_number(value) for value in published.values()):
        check.fail("published", published, f"a dict of finite numbers for some of {', '.join(PUBLISHED_FIELDS)}")


def read_printed(read: FieldReader, table, design: dict) -> dict:
    """[printed]: m12, center_distance (mm) and teeth as a paper prints them for ``design``."""
    read.keys(table, {"m12", "center_distance", "teeth"}, "printed")
    values = {}
    for key in ("m12", "center_distance"):
        if key in table:
            values[key] = read.number(table, key, "printed")
            if values[key] <= 0:
                read.fail(f"printed.{key}", values[key], "a positive number")
    if "center_distance" in values and values["center_distance"] <= design["l"] + design["b"]:
        read.fail("printed.center_distance", values["center_distance"],
                  f"more than the largest driver radius l + b = {design['l'] + design['b']:g} mm")
    if "teeth" in table:
        values["teeth"] = read.integer(table, "teeth", "printed", 3, 100000)
    return values


def read_published(read: FieldReader, table) -> dict:
    """[published]: the figures a paper reports for the design (``PUBLISHED_FIELDS``)."""
    read.keys(table, set(PUBLISHED_FIELDS), "published")
    return {key: read.number(table, key, "published") for key in PUBLISHED_FIELDS if key in table}


def _choice(read: FieldReader, table: dict, key: str, where: str, options, default):
    value = table.get(key, default)
    if value not in options:
        read.fail(f"{where}.{key}", value, " or ".join(f'"{o}"' for o in options))
    return value


def _positive(read: FieldReader, table: dict, key: str, where: str, default: float) -> float:
    if key not in table:
        return default
    value = read.number(table, key, where)
    if value <= 0:
        read.fail(f"{where}.{key}", value, "a positive number")
    return value


def _interval(read: FieldReader, value, field: str, expected: str) -> tuple[float, float]:
    if (not is_sequence(value) or len(value) != 2 or not all(is_finite_number(v) for v in value)
            or not value[0] < value[1]):
        read.fail(field, value, expected)
    return float(value[0]), float(value[1])


def _bounds(read: FieldReader, table, design: dict) -> dict:
    read.keys(table, set(FILE_NAMES.values()), "search.bounds")
    bounds = {}
    for name in VARIABLES:
        key = FILE_NAMES[name]
        if key not in table:
            continue
        field_name = f"search.bounds.{key}"
        if name in TRANSLATION_ONLY:
            read.fail(field_name, table[key], f"no bounds: {key} only translates the path (every objective's "
                      "derivative with respect to it is zero), so it stays fixed at its [design] value")
        low, high = _interval(read, table[key], field_name, "[low, high] with low < high")
        if name == "alpha":
            low, high = float(np.radians(low)), float(np.radians(high))
        elif low <= 0:
            read.fail(field_name, table[key], "positive bounds")
        if name == "m11" and low <= 0.5:
            read.fail(field_name, table[key], "bounds above 0.5 (eq 2)")
        bounds[name] = (low, high)
    b_high = bounds.get("b", (design["b"],) * 2)[1]
    l_low = bounds.get("l", (design["l"],) * 2)[0]
    if b_high >= l_low:
        key = "search.bounds.b" if "b" in bounds else "search.bounds.l"
        read.fail(key, table.get("b" if "b" in bounds else "l"), f"b below l everywhere in the bounds (largest b "
                  f"{b_high:g} mm, smallest l {l_low:g} mm): the driver radius l - b would reach zero and the gear "
                  "could not close")
    return bounds


def parse_problem(data: dict, source: str = "<dict>") -> ParallelogramProblem:
    """Validate a problem given as a dict with the fields of the file (mm, degrees, rpm).

    Raises
    ------
    ProblemError
        Naming the source, the field, the value and what was expected.
    """
    from transplanter.parallelogram.tolerance_model import DIMENSION_NAMES  # it reads problems: imported here

    read = FieldReader(source)
    read.keys(data, _TOP_KEYS, "")
    if "design" not in data:
        raise ProblemError(f"{source}: [design] is missing: "
                           f"expected the eight variables {', '.join(FILE_NAMES.values())}")
    design = read_design(read, data["design"])
    gear = data.get("gear", {})
    read.keys(gear, {"module", "pressure_angle_deg", "face_width_mm"}, "gear")
    pressure = read.number(gear, "pressure_angle_deg", "gear") if "pressure_angle_deg" in gear else 20.0
    if not 5 <= pressure <= 35:
        read.fail("gear.pressure_angle_deg", pressure, "an angle from 5 to 35 degrees")
    machine = data.get("machine", {})
    read.keys(machine, {"driver_speed_rpm", "forward_speed_mm_s", "forward", "crank_pivot_mm"}, "machine")
    rpm = _positive(read, machine, "driver_speed_rpm", "machine", 60.0)
    speed = _positive(read, machine, "forward_speed_mm_s", "machine", 300.0)
    conventions = data.get("conventions", {})
    read.keys(conventions, {"crank_sense", "alpha_reference_deg", "alpha_instant"}, "conventions")
    reference = (read.number(conventions, "alpha_reference_deg", "conventions")
                 if "alpha_reference_deg" in conventions else -90.0)
    objectives = data.get("objectives", {})
    read.keys(objectives, {"depth_window_mm", "depth_target_mm", "depth_band_mm", "vertical_range_target_mm"},
              "objectives")
    band = _interval(read, objectives.get("depth_band_mm", [25.0, 30.0]), "objectives.depth_band_mm",
                     "[low, high] in mm with 0 < low < high")
    if band[0] <= 0:
        read.fail("objectives.depth_band_mm", objectives["depth_band_mm"], "[low, high] in mm with 0 < low < high")
    target = _positive(read, objectives, "depth_target_mm", "objectives", 25.0)
    if not band[0] <= target <= band[1]:
        read.fail("objectives.depth_target_mm", target, f"a depth within objectives.depth_band_mm {list(band)} (the "
                                                        "search keeps its designs in the band)")
    search = data.get("search", {})
    read.keys(search, {"population", "generations", "seed", "bounds"}, "search")
    population = read.integer(search, "population", "search", 8, LARGEST_POPULATION, default=100)
    generations = read.integer(search, "generations", "search", 1, 100000, default=100)
    if population * generations > MAX_EVALUATIONS:
        read.fail("search.generations", generations, f"at most {MAX_EVALUATIONS // population} with search.population "
                                                     f"= {population}: population x generations up to "
                                                     f"{MAX_EVALUATIONS:.0e} evaluations (the default 1e4 takes about "
                                                     f"1 s, so 1e6 about 2 min)")
    return ParallelogramProblem(
        design=design,
        module=_positive(read, gear, "module", "gear", 2.0),
        pressure_angle=float(np.radians(pressure)),
        driver_speed=rpm * 2 * np.pi / 60, forward_speed=speed,
        crank_pivot=read.point(machine.get("crank_pivot_mm", [0.0, 0.0]), "machine.crank_pivot_mm"),
        conventions=Conventions(
            crank_sense=SENSES[_choice(read, conventions, "crank_sense", "conventions", SENSES, "counterclockwise")],
            alpha_reference=float(np.radians(reference)),
            alpha_instant=_choice(read, conventions, "alpha_instant", "conventions", INSTANTS, "slowest"),
            forward=DIRECTIONS[_choice(read, machine, "forward", "machine", DIRECTIONS, "-x")]),
        depth_window=_positive(read, objectives, "depth_window_mm", "objectives", 0.5),
        depth_target=target,
        depth_band=band,
        vertical_range_target=_positive(read, objectives, "vertical_range_target_mm", "objectives", 160.0),
        bounds=_bounds(read, search.get("bounds", {}), design),
        population=population, generations=generations,
        seed=read.integer(search, "seed", "search", 0, 2**31 - 1, default=1),
        source=source, title=read.text(data, "title", "", LONGEST_TITLE),
        printed=read_printed(read, data.get("printed", {}), design),
        published=read_published(read, data.get("published", {})),
        tolerances=parse_tolerances(data.get("tolerances", {}), DIMENSION_NAMES, source),
        solid_sizes=read_solid_sizes(read, gear, "gear"))

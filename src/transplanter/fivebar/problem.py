"""TOML five-bar problem files (mm, degrees) -> a validated ``FiveBarProblem`` (mm, radians).

Schema (docs/fivebar.md, "Problem files"); the carrier pivot O is the origin:

    title = "..."
    [[key_poses]]                 # exactly four: P of the push plate and the plate direction
    label = "P1"
    x = -23.1                     # mm; any of x, y, angle_deg, carrier_turn_deg may be a band [low, high]
    y = -309.7
    angle_deg = 113.8             # plate direction, counterclockwise from +x
    carrier_turn_deg = 0.0        # how far the carrier has turned clockwise since pose 1 (0 at pose 1)
    [[return_points]]             # positions of P on the return stroke (no angle)
    x = -125.0
    y = -287.0
    [ranges]                      # optional [low, high] limits (Wang et al. 2025 Table 2)
    ep = [55, 100]                # |EP| mm
    fp = [20, 100]                # |FP| mm
    x_e = [-100, 0]               # x of E in pose 1, mm
    x_f = [-20, 50]               # x of F in pose 1, mm
    [conditions]
    min_closure_margin = 0.01     # sin^2(angle EBF) kept above this all round (eq 10 without scale)
    ratio = [0.25, 4.0]           # bounds on the total ratio i0 = dc / drho (eq 11)
    return_tolerance_mm = 1.0     # how far P may pass from each return point (mm, >= 0)
    min_transmission_angle_deg = 40.0   # optional floor on the transmission angle at E, in (0, 90)
    [requirements]                # optional, between the poses the design chooses (fivebar/key_pose_bands.py)
    max_offset_from_first_mm = [130.0, 10.0]
    min_stroke_mm = 110.0
    max_last_step_mm = 40.0
    [spline]
    control_points = 12           # periodic cubic B-spline of the relative angle
    [region]
    samples = 1000                # pencil lines per 4-pose curve, 64-8000 (five-bars judged grow as its square)
    radius_mm = 600.0             # hinges within this distance of the poses' centroid
    band_samples = 16             # pose sets drawn inside the bands when their centres give no five-bar
    [gears]
    module = 1.5                  # mm, 0.2-10: pitch perimeters are pi * module * whole teeth
    pressure_angle_deg = 20.0     # 14.5-30
    max_pressure_angle_deg = 45.0 # largest pressure angle of a mesh over the turn, above pressure_angle_deg, below 90
    cutter = "rack"               # "rack" (a stage with a concave stretch is shaper-cut, with the reason) or "shaper"
    shaper_teeth = 16             # teeth of the shaper cutter, 8-200
    layout = "bent"               # "bent": intermediate shaft off O-A; "straight": a1 + a2 = |OA|
    first_center_distance = 93.8  # optional, both or neither: a1, a2 (mm) fixed instead of searched;
    second_center_distance = 122. # they must give whole teeth at the module
    face_width_mm = 15.0          # optional: the gears' solids (solids/sizes.py; default 10 modules)
    [support]                     # optional: the seedling support timed to the design (fivebar/support_problem.py)
    [load]                        # optional: the planting load and link masses (fivebar/load_spec.py)
    [shafts]                      # optional: shaft and hinge-pin diameters (fivebar/shaft_spec.py)
    [plates]                      # optional: thickness_mm of the link plates' solids (solids/sizes.py)
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from transplanter.burmester.problem import check_distinct
from transplanter.fivebar.key_pose_bands import (
    PoseBands,
    Requirements,
    as_given,
    check_bands_meet_requirements,
    read_key_pose_rows,
    read_requirements,
    stroke_direction,
)
from transplanter.fivebar.load_spec import LoadSpec, parse_load
from transplanter.fivebar.shaft_spec import ShaftSpec, parse_shafts
from transplanter.fivebar.support_problem import SupportSpec, parse_support
from transplanter.fivebar.tolerance_model import DIMENSION_NAMES
from transplanter.solids.sizes import SolidSizes, read_solid_sizes
from transplanter.tolerance.dimensions import ToleranceSettings, parse_tolerances
from transplanter.toml_fields import LONGEST_LABEL, LONGEST_TITLE, ClassFields, FieldReader, read_toml, warn_if_radians
from transplanter.trains.toothed_train import (
    CUTTERS,
    LAYOUTS,
    MODULE_RANGE,
    PRESSURE_ANGLE_RANGE_DEG,
    SHAPER_TEETH_RANGE,
    Gearing,
)

RANGE_FIELDS = {"ep": "|EP| (mm)", "fp": "|FP| (mm)", "x_e": "x of E in pose 1 (mm)", "x_f": "x of F in pose 1 (mm)"}
#: Most control points of the relative angle's periodic spline (a design NLP variable each).
MOST_CONTROL_POINTS = 72
_TOP_KEYS = {"title", "description", "key_poses", "return_points", "ranges", "conditions", "requirements", "spline",
             "region", "gears",
             "support", "load", "tolerances", "shafts", "plates"}


@dataclass(frozen=True)
class FiveBarProblem:
    """A validated five-bar problem, in mm and radians (``parse_problem`` takes degrees).

    Attributes
    ----------
    poses : ndarray, shape (4, 3)
        Key poses of the push plate: x, y of P (mm) and the plate direction (rad,
        counterclockwise from +x, within one turn of zero); the bands' centres where ``pose_bands`` has bands.
    carrier_turns : ndarray, shape (4,)
        Clockwise turn of the carrier since pose 1 (rad): 0 first, strictly increasing, below 2 pi.
    return_points : ndarray, shape (m, 2)
        Positions of P on the return stroke (mm), m >= 1.
    labels, return_labels : tuple of str
        Names of the key poses (4) and of the return points (m).
    ranges : dict
        Optional ``name -> (low, high)`` limits of ``RANGE_FIELDS`` (mm).
    min_closure_margin : float
        sin^2 of the smallest angle EBF allowed over the turn, in (0, 1).
    ratio_bounds : (float, float)
        Bounds on the total ratio i0 = dc / drho, 0 < low < high.
    return_tolerance_mm : float
        Largest distance of P from each return point (mm, >= 0; 0 makes them exact).
    spline_count : int
        Control points of the periodic B-spline of the relative angle.
    samples : int
        Pencil lines tracing each 4-pose curve of the solution region.
    radius_mm : float
        Hinges are kept within this distance of the poses' centroid (mm).
    gearing : Gearing
        Module, pressure angle, cutter, carrier layout and optional fixed centre distances of the gear train
        (``trains.toothed_train``); ``center_distances`` gives its fixed centre distances (mm) or None.
    support : SupportSpec or None
        The seedling support to design with the five-bar (``[support]``); None: none.
    pose_bands : PoseBands or None
        Bands of the key poses' x, y, direction and carrier turn (mm, rad), or None when all are exact.
    requirements : Requirements
        The relative requirements between the chosen key poses (mm).
    band_samples : int
        Pose sets drawn inside the bands when the region at their centres holds no feasible five-bar.
    min_transmission_angle : float or None
        Floor on the transmission angle at E over the turn (rad), or None.
    load : LoadSpec
        The planting load at P and the links' masses for the kinetostatics (``[load]``; default 20 N against P's
        velocity over the pushing stroke, no masses).
    shafts : ShaftSpec
        Given shaft and hinge-pin diameters (``[shafts]``, mm); the rest are sized by ``shafts.sizing``.
    solid_sizes : SolidSizes
        The gears' face width (``[gears]``) and the link plates' thickness (``[plates]``) of the STEP solids (mm);
        None takes the rules of ``solids.sizes``.
    source, title : str
        Where the problem came from (file name or ``"<dict>"``) and its title.
    tolerances : ToleranceSettings
        The ``[tolerances]`` table: tolerances of the built mechanism's dimensions (``fivebar.tolerance_model``)
        and the analysis settings (``tolerance.dimensions``).

    Raises
    ------
    ProblemError
        When a field has the wrong shape, a value that is not finite, or angles that look like degrees.
    """

    poses: np.ndarray
    carrier_turns: np.ndarray
    return_points: np.ndarray
    labels: tuple[str, ...]
    return_labels: tuple[str, ...]
    ranges: dict = field(default_factory=dict)
    min_closure_margin: float = 0.01
    ratio_bounds: tuple[float, float] = (0.25, 4.0)
    return_tolerance_mm: float = 1.0
    spline_count: int = 12
    samples: int = 1000
    radius_mm: float = 600.0
    gearing: Gearing = field(default_factory=Gearing)
    support: SupportSpec | None = None
    pose_bands: PoseBands | None = None
    requirements: Requirements = field(default_factory=Requirements)
    band_samples: int = 16
    min_transmission_angle: float | None = None
    load: LoadSpec = field(default_factory=LoadSpec)
    shafts: ShaftSpec = field(default_factory=lambda: ShaftSpec({}))
    solid_sizes: SolidSizes = field(default_factory=SolidSizes)
    source: str = "<dict>"
    title: str = ""
    tolerances: ToleranceSettings = field(default_factory=ToleranceSettings)

    def __post_init__(self):
        check = ClassFields(self)
        poses = check.array("poses", (4, 3))
        check.angles_within_a_turn("poses", poses[:, 2])
        turns = check.array("carrier_turns", (4,))
        if turns[0] != 0 or np.any(np.diff(turns) <= 0) or turns[-1] >= 2 * np.pi:
            check.fail("carrier_turns", turns, "0 at the first pose, then strictly increasing and below 2 pi rad")
        points = check.array("return_points", (None, 2), minimum=1)
        if len(self.labels) != 4 or len(self.return_labels) != len(points):
            check.fail("labels", (self.labels, self.return_labels), "4 key-pose labels and one per return point")
        if not 0 < self.min_closure_margin < 1:
            check.fail("min_closure_margin", self.min_closure_margin, "a number in (0, 1)")
        low, high = self.ratio_bounds
        if not 0 < low < high:
            check.fail("ratio_bounds", self.ratio_bounds, "0 < low < high")
        if not (np.isfinite(self.return_tolerance_mm) and self.return_tolerance_mm >= 0):
            check.fail("return_tolerance_mm", self.return_tolerance_mm, "a finite distance >= 0 (mm)")
        check.positive("radius_mm")
        if not isinstance(self.gearing, Gearing):
            check.fail("gearing", self.gearing, "a trains.toothed_train.Gearing")
        if self.support is not None and not isinstance(self.support, SupportSpec):
            check.fail("support", self.support, "None or a fivebar.support_problem.SupportSpec")
        if not isinstance(self.load, LoadSpec):
            check.fail("load", self.load, "a fivebar.load_spec.LoadSpec")
        if not isinstance(self.shafts, ShaftSpec):
            check.fail("shafts", self.shafts, "a fivebar.shaft_spec.ShaftSpec")
        if not isinstance(self.solid_sizes, SolidSizes):
            check.fail("solid_sizes", self.solid_sizes, "a solids.sizes.SolidSizes")
        if self.pose_bands is not None and not isinstance(self.pose_bands, PoseBands):
            check.fail("pose_bands", self.pose_bands, "None or a fivebar.key_pose_bands.PoseBands")
        if not isinstance(self.requirements, Requirements):
            check.fail("requirements", self.requirements, "a fivebar.key_pose_bands.Requirements")
        check.whole("band_samples", 0, 10000)
        if self.min_transmission_angle is not None:
            check.number("min_transmission_angle", 0.0, np.pi / 2, "None or an angle in [0, pi/2] rad")

    @property
    def stroke_direction(self) -> float:
        """+1 when P moves towards -x from the first key pose to the last (``key_pose_bands``), else -1."""
        return stroke_direction(self.poses)

    def with_poses(self, poses: np.ndarray, carrier_turns: np.ndarray) -> FiveBarProblem:
        """The problem with exact key poses (mm, rad): the ones a design chose inside the bands, or a pose set
        drawn from them."""
        return dataclasses.replace(self, poses=np.array(poses, float), carrier_turns=np.array(carrier_turns, float),
                                   pose_bands=None)

    @property
    def center_distances(self) -> tuple[float, float] | None:
        """Sun to intermediate shaft and intermediate shaft to planet (mm) when the problem fixes them."""
        return self.gearing.center_distances


def load_problem(path: str | Path) -> FiveBarProblem:
    """Read and validate a five-bar problem file (TOML, mm and degrees; schema above).

    Raises
    ------
    ProblemError
        Naming the file, the field, the value and what was expected.
    """
    return parse_problem(read_toml(path), str(path))


def _pair(read: FieldReader, table: dict, key: str, where: str) -> tuple[float, float]:
    values = read.numbers(table, key, where, 2)
    low, high = values[0], values[-1]
    if len(values) != 2 or not low < high:
        read.fail(f"{where}.{key}", table[key], "[low, high] with low < high")
    return float(low), float(high)


def _table_rows(read: FieldReader, data: dict, key: str, fields: tuple[str, ...]):
    rows = read.tables(data, key, f"an array of tables [[{key}]] with {', '.join(fields)}")
    values, labels = [], []
    for k, row in enumerate(rows):
        where = f"{key}[{k}]"
        read.keys(row, set(fields) | {"label"}, where)
        values.append([read.number(row, name, where) for name in fields])
        labels.append(read.text(row, "label", where, LONGEST_LABEL))
    return np.array(values, float).reshape(-1, len(fields)), labels


def _choice(read: FieldReader, table: dict, key: str, choices: tuple[str, ...], why: str) -> str:
    value = table.get(key, choices[0])
    if value not in choices:
        read.fail(f"gears.{key}", value, " or ".join(f'"{c}"' for c in choices) + why)
    return value


def _gearing(read: FieldReader, table: dict) -> Gearing:
    """The [gears] table: module, pressure angle, cutter, layout and optional fixed centre distances."""
    read.keys(table, {"module", "pressure_angle_deg", "cutter", "shaper_teeth", "layout", "first_center_distance",
                      "second_center_distance", "max_pressure_angle_deg", "face_width_mm"}, "gears")
    module = read.number(table, "module", "gears") if "module" in table else 1.5
    if not MODULE_RANGE[0] <= module <= MODULE_RANGE[1]:
        read.fail("gears.module", module, f"a module from {MODULE_RANGE[0]:g} to {MODULE_RANGE[1]:g} mm (finer gives "
                                          "hundreds of teeth on these gears, coarser a few tens of mm per tooth)")
    pressure = read.number(table, "pressure_angle_deg", "gears") if "pressure_angle_deg" in table else 20.0
    low, high = PRESSURE_ANGLE_RANGE_DEG
    if not low <= pressure <= high:
        read.fail("gears.pressure_angle_deg", pressure, f"an angle from {low:g} to {high:g} deg (the standard ones; "
                                                       "smaller needs ever larger gears against rack undercut, larger "
                                                       "makes pointed teeth)")
    cutter = _choice(read, table, "cutter", CUTTERS, "")
    layout = _choice(read, table, "layout", LAYOUTS, " (intermediate shaft off O-A, or on it)")
    teeth = read.integer(table, "shaper_teeth", "gears", *SHAPER_TEETH_RANGE, default=16)
    keys = ("first_center_distance", "second_center_distance")
    centers = None
    if any(key in table for key in keys):
        if not all(key in table for key in keys):
            read.fail("gears", {k: table[k] for k in keys if k in table},
                      "both first_center_distance and second_center_distance (mm), or neither")
        centers = (read.number(table, keys[0], "gears"), read.number(table, keys[1], "gears"))
        if min(centers) <= 0:
            read.fail("gears", {k: table[k] for k in keys}, "positive center distances (mm)")
    limit = read.number(table, "max_pressure_angle_deg", "gears") if "max_pressure_angle_deg" in table else 45.0
    if not pressure < limit < 90:
        read.fail("gears.max_pressure_angle_deg", limit, f"an angle above gears.pressure_angle_deg ({pressure:g}) and "
                                                         "below 90 deg (the mesh's push along the motion falls as its "
                                                         "cosine)")
    return Gearing(module, float(np.radians(pressure)), cutter, teeth, layout, centers, float(np.radians(limit)))


def _check_return_points(read: FieldReader, key: np.ndarray, points: np.ndarray, radius: float):
    """Refuse a return point on a key pose (the stroke's order is then undefined) or beyond reach:
    the hinges lie within ``radius`` of the key poses' centroid, and so P within 2 ``radius`` plus
    the farthest key pose of it. A radius smaller than the key poses' spread is left to the region,
    which names it (no chain reaches the key poses then)."""
    centre = key.mean(axis=0)
    spread = np.linalg.norm(key - centre, axis=1).max()
    reach = 2 * radius + spread
    for k, point in enumerate(points):
        gaps = np.linalg.norm(key - point, axis=1)
        if gaps.min() <= 1e-9 * spread:
            read.fail(f"return_points[{k}]", point.tolist(), f"a point of the return stroke apart from the key "
                                                            f"poses (it is on key_poses[{int(np.argmin(gaps))}])")
        distance = np.linalg.norm(point - centre)
        if distance > reach and radius >= spread:
            read.fail(f"return_points[{k}]", point.tolist(),
                      f"a point P can reach: it is {distance:.6g} mm from the key poses' centroid, and with the hinges "
                      f"within region.radius_mm = {radius:g} mm of it P stays within {reach:.6g} mm")


def parse_problem(data: dict, source: str = "<dict>") -> FiveBarProblem:
    """Validate a five-bar problem given as a dict with the fields of the file (mm, degrees).

    Parameters
    ----------
    data : dict
        The file's tables as dicts; a list of numbers may be a tuple or a numpy array.
    source : str
        Named in error messages (the file name when read from a file).

    Returns
    -------
    FiveBarProblem
        In mm and radians.

    Raises
    ------
    ProblemError
        Naming the source, the field, the value and what was expected.
    """
    read = FieldReader(source)
    read.keys(data, _TOP_KEYS, "")
    low, high, labels = read_key_pose_rows(
        read, read.tables(data, "key_poses", "an array of tables [[key_poses]] with x, y, angle_deg, carrier_turn_deg"))
    if len(low) != 4:
        read.fail("key_poses", f"{len(low)} poses",
                  "exactly 4 key poses (the 4-pose solution region of Wang et al. 2025)")
    rows = (low + high) / 2
    if np.any(np.abs(np.r_[low[:, 2], high[:, 2]]) > 360):
        read.fail("key_poses[].angle_deg", as_given(low[:, 2], high[:, 2]),
                  "plate directions within one turn of zero (|angle_deg| <= 360)")
    turns = rows[:, 3]
    if high[0, 3] != 0 or low[0, 3] != 0:
        read.fail("key_poses[0].carrier_turn_deg", as_given(low[:1, 3], high[:1, 3])[0],
                  "0: the carrier's turn counts from pose 1")
    if np.any(low[1:, 3] <= high[:-1, 3]) or high[-1, 3] >= 360:
        read.fail("key_poses[].carrier_turn_deg", as_given(low[:, 3], high[:, 3]),
                  "turns (or bands of turns) strictly increasing from 0 and below 360, each band ending before the "
                  "next pose's begins (overlapping bands would let two poses swap order)")
    check_distinct(read, rows, "key_poses")
    warn_if_radians(source, "key_poses[].angle_deg", rows[:, 2])
    warn_if_radians(source, "key_poses[].carrier_turn_deg", rows[:, 3])
    points, return_labels = _table_rows(read, data, "return_points", ("x", "y"))
    if len(points) == 0:
        read.fail("return_points", [], "at least one point of the return stroke (Wang et al. 2025 Table 3 has five)")
    if len(points) > MOST_CONTROL_POINTS - 4:
        read.fail("return_points", f"{len(points)} points", f"at most {MOST_CONTROL_POINTS - 4} (the relative angle's "
                  f"spline, at most {MOST_CONTROL_POINTS} control points, takes four more than the return points)")
    labels = [label or f"P{k + 1}" for k, label in enumerate(labels)]
    return_labels = [label or f"P{k + 5}" for k, label in enumerate(return_labels)]

    ranges_table = data.get("ranges", {})
    read.keys(ranges_table, set(RANGE_FIELDS), "ranges")
    ranges = {key: _pair(read, ranges_table, key, "ranges") for key in ranges_table}
    for key in ("ep", "fp"):
        if key in ranges and (ranges[key][0] <= 0 if key == "ep" else ranges[key][0] < 0):
            start = "above" if key == "ep" else "at or above"
            read.fail(f"ranges.{key}", ranges_table[key], f"a length range (mm) that starts {start} zero")

    requirements = read_requirements(read, data.get("requirements", {}))
    check_bands_meet_requirements(read, low, high, requirements, stroke_direction(rows))

    conditions = data.get("conditions", {})
    read.keys(conditions, {"min_closure_margin", "ratio", "return_tolerance_mm", "min_transmission_angle_deg"},
              "conditions")
    transmission = None
    if "min_transmission_angle_deg" in conditions:
        transmission = read.number(conditions, "min_transmission_angle_deg", "conditions")
        if not 0 <= transmission < 90:
            read.fail("conditions.min_transmission_angle_deg", transmission,
                      "an angle from 0 to below 90 deg: the least transmission angle at E allowed over the turn")
    margin = read.number(conditions, "min_closure_margin", "conditions") if "min_closure_margin" in conditions else 0.01
    if not 0 < margin < 1:
        read.fail("conditions.min_closure_margin", margin, "a number in (0, 1): sin^2 of the smallest angle EBF")
    ratio = _pair(read, conditions, "ratio", "conditions") if "ratio" in conditions else (0.25, 4.0)
    if ratio[0] <= 0:
        read.fail("conditions.ratio", list(ratio), "positive bounds (a ratio <= 0 reverses the gears)")
    tolerance = (read.number(conditions, "return_tolerance_mm", "conditions") if "return_tolerance_mm" in conditions
                 else 1.0)
    if not (np.isfinite(tolerance) and tolerance >= 0):
        read.fail("conditions.return_tolerance_mm", tolerance, "a finite distance >= 0 (mm) from each return point")

    spline = data.get("spline", {})
    read.keys(spline, {"control_points"}, "spline")
    count = read.integer(spline, "control_points", "spline", len(points) + 4, MOST_CONTROL_POINTS,
                         default=max(12, len(points) + 4))

    region = data.get("region", {})
    read.keys(region, {"samples", "radius_mm", "band_samples"}, "region")
    samples = read.integer(region, "samples", "region", 64, 8000, default=1000)   # 6000: 48 s, every candidate refined
    band_samples = read.integer(region, "band_samples", "region", 0, 10000, default=16)
    radius = read.number(region, "radius_mm", "region") if "radius_mm" in region else 600.0
    if radius <= 0:
        read.fail("region.radius_mm", radius, "a positive distance (mm)")

    gearing = _gearing(read, data.get("gears", {}))
    _check_return_points(read, rows[:, :2], points, radius)
    support = parse_support(read, data["support"], ranges.get("x_e")) if "support" in data else None
    load = parse_load(read, data.get("load", {}))
    shafts = parse_shafts(read, data.get("shafts", {}))
    solid_sizes = read_solid_sizes(read, data.get("gears", {}), "gears", data.get("plates", {}))

    poses = rows[:, :3].copy()
    poses[:, 2] = np.radians(poses[:, 2])
    to_internal = np.array([1.0, 1.0, np.pi / 180, np.pi / 180])
    bands = PoseBands(low * to_internal, high * to_internal) if np.any(high > low) else None
    return FiveBarProblem(poses=poses, carrier_turns=np.radians(turns), return_points=points, labels=tuple(labels),
                          return_tolerance_mm=tolerance, pose_bands=bands, requirements=requirements,
                          band_samples=band_samples, load=load, shafts=shafts, solid_sizes=solid_sizes,
                          min_transmission_angle=None if transmission is None else float(np.radians(transmission)),
                          return_labels=tuple(return_labels), ranges=ranges, min_closure_margin=margin,
                          ratio_bounds=ratio, spline_count=count, samples=samples, radius_mm=radius,
                          gearing=gearing, support=support, source=source,
                          title=read.text(data, "title", "", LONGEST_TITLE),
                          tolerances=parse_tolerances(data.get("tolerances", {}), DIMENSION_NAMES, source))

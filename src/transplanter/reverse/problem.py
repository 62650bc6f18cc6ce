"""TOML reverse-design problem files (mm, degrees) -> a validated ``ReverseProblem``.

Schema (docs/reverse.md, "Problem files"):

    title = "..."
    [trajectory]
    kind = "control_points"       # or "samples": points on the curve, interpolated
    points = [[x, y], ...]        # mm, in the order the tip runs through them; at least 4
    [arm]
    pivot = [0.0, 0.0]            # carrier center, mm (default the origin)
    carrier_length = 92.3         # s, mm; give both lengths or neither (then the rice-transplanter paper eq 1-2)
    arm_length = 162.0            # l, mm
    direction = "clockwise"       # carrier rotation, or "counterclockwise" (default)
    branch = "auto"               # at the first point: "approach", "retraction" or "auto"
    [train]
    topology = "sun-intermediate-planet"   # or "sun-idler-planet" (3 gears),
                                           # "pick-up" (the cusp-pitch-curve paper eq 15)
    split = "sqrt"                # or "peak_to_valley" (4 gears), "identical_sun_planet" (3 gears)
    # peak_to_valley = 0.6        # with split = "peak_to_valley" only: its b, in (0, 1)
    center_distances = [46.15, 46.15]      # mm; default s/2 each (collinear carrier)
    module = 2.5                  # mm, of the whole teeth (default 2.5)
    cutter = "rack"               # or "shaper" (16 teeth): how the four-gear train's teeth are cut
    face_width_mm = 25.0          # of the gears' STEP solids (default solids.sizes.FACE_WIDTH_MODULES modules)
    [tolerances]                  # optional: the built train's tolerances and the analysis (docs/tolerance.md)
    path_accuracy_mm = 2.5        # the built tip within this of the path over the turn (default 1 % of s + l)
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from transplanter.reverse.tolerance_model import PATH_ACCURACY_KEY, dimension_names
from transplanter.solids.sizes import SolidSizes, read_solid_sizes
from transplanter.tolerance.dimensions import ToleranceSettings, parse_tolerances
from transplanter.toml_fields import (
    LONGEST_TITLE,
    MAGNITUDE_LIMIT,
    SMALLEST_LENGTH,
    ClassFields,
    FieldReader,
    is_finite_number,
    is_sequence,
    read_toml,
)
from transplanter.trains.toothed_train import CUTTERS

TOPOLOGIES = {"sun-intermediate-planet": ("sqrt", "peak_to_valley"),
              "pick-up": ("sqrt", "peak_to_valley"),
              "sun-idler-planet": ("identical_sun_planet",)}
_TOP_KEYS = {"title", "description", "trajectory", "arm", "train", "tolerances"}
#: Most points of a path: time and memory grow with their number (measured on the rice example's loop sampled
#: evenly: 5000 points 29 s and 0.1 GB, 100,000 points 185 s and 0.53 GB), and a loop sampled more finely than this
#: gives the same train.
LARGEST_POINT_COUNT = 20000
#: The closing gap (last point back to the first) may be at most this many times the longest other gap.
OPEN_GAP_FACTOR = 3.0


@dataclass(frozen=True)
class ReverseProblem:
    """A validated reverse-design problem, in mm.

    Attributes
    ----------
    points : ndarray, shape (N, 2)
        The closed path of the arm tip relative to the pivot (mm), N >= 4, in running order.
    kind : str
        ``"control_points"`` of a closed B-spline or ``"samples"`` on the curve.
    pivot : ndarray, shape (2,)
        The carrier center (mm).
    lengths : (float, float) or None
        Carrier and arm lengths (mm); None: from the path's farthest and nearest points.
    direction : int
        +1 counterclockwise carrier, -1 clockwise.
    branch : str
        Arm branch at the first point: ``"approach"``, ``"retraction"`` or ``"auto"``.
    topology, split : str
        Gear train (``TOPOLOGIES``) and how the total ratio is split over its stages.
    peak_to_valley : float
        Share of the ratio's swing stage 1 carries, in (0, 1).
    center_distances : (float, float) or None
        mm; None: half the carrier each.
    module : float
        mm, of the four-gear train's whole teeth.
    cutter : str
        ``"rack"`` (a stage with a hollow goes to the shaper) or ``"shaper"`` (``trains.toothed_train.Gearing``).
    source, title : str
        Where the problem came from and its title.
    solid_sizes : SolidSizes
        The gears' face width for their STEP solids (``train.face_width_mm``); None: the rule of ``solids.sizes``.
    tolerances : ToleranceSettings
        The ``[tolerances]`` table: tolerances of the built train's dimensions (``reverse.tolerance_model``) and
        the analysis settings (``tolerance.dimensions``).
    path_accuracy_mm : float or None
        How far (mm) a built train's tip may stray from the path over the turn, the tolerance analysis's hard
        condition; None: ``reverse.tolerance_model.PATH_ACCURACY`` of the reach s + l.

    Raises
    ------
    ProblemError
        When a field has the wrong shape or a value out of range.
    """

    points: np.ndarray
    kind: str
    pivot: np.ndarray
    lengths: tuple[float, float] | None
    direction: int
    branch: str
    topology: str = "sun-intermediate-planet"
    split: str = "sqrt"
    peak_to_valley: float = 0.5
    center_distances: tuple[float, float] | None = None
    module: float = 2.5
    cutter: str = "rack"
    source: str = "<dict>"
    title: str = ""
    solid_sizes: SolidSizes = field(default_factory=SolidSizes)
    tolerances: ToleranceSettings = field(default_factory=ToleranceSettings)
    path_accuracy_mm: float | None = None

    def __post_init__(self):
        check = ClassFields(self)
        points = check.array("points", (None, 2), minimum=4)
        check_closed_curve(points, check.fail, "points")
        check.array("pivot", (2,))
        check.choice("kind", ("control_points", "samples"))
        for name in ("lengths", "center_distances"):
            pair = getattr(self, name)
            if pair is None:
                continue
            values = np.asarray(pair, float) if is_sequence(pair) and all(map(is_finite_number, pair)) else None
            if values is None or values.shape != (2,) or values.min() <= 0 or values.max() > MAGNITUDE_LIMIT:
                check.fail(name, pair, "two positive lengths (mm), or None")
            object.__setattr__(self, name, (float(values[0]), float(values[1])))
        check.choice("direction", (1, -1))
        check.choice("branch", ("auto", "approach", "retraction"))
        check.choice("topology", tuple(TOPOLOGIES))
        if self.split not in TOPOLOGIES[self.topology]:
            check.fail("split", (self.topology, self.split), f"a topology and split of {TOPOLOGIES}")
        check.number("peak_to_valley", 1e-12, 1 - 1e-12, "a number in (0, 1)")
        check.positive("module")
        check.choice("cutter", CUTTERS)
        check.text("source", "title")
        check.positive("path_accuracy_mm", optional=True)
        if not isinstance(self.solid_sizes, SolidSizes):
            check.fail("solid_sizes", self.solid_sizes, "a solids.sizes.SolidSizes")


def load_problem(path: str | Path) -> ReverseProblem:
    """Read and validate a reverse-design file (TOML, mm and degrees; schema above).

    Raises
    ------
    ProblemError
        Naming the file, the field, the value and what was expected.
    """
    return parse_problem(read_toml(path), str(path))


def _choice(read: FieldReader, table: dict, key: str, where: str, options, default=None) -> str:
    value = table.get(key, default)
    if not isinstance(value, str) or value not in options:
        read.fail(f"{where}.{key}", value, "one of " + ", ".join(f'"{o}"' for o in options))
    return value


def _trajectory_points(read: FieldReader, table: dict) -> tuple[np.ndarray, str]:
    read.keys(table, {"kind", "points"}, "trajectory")
    kind = _choice(read, table, "kind", "trajectory", ("control_points", "samples"))
    points = read.points(table, "points", "trajectory", largest=LARGEST_POINT_COUNT)
    size = np.ptp(points, axis=0).max() if len(points) else 0.0      # the path's own size: tolerances follow it
    if len(points) > 4 and np.linalg.norm(points[0] - points[-1]) <= 1e-9 * size:
        points = points[:-1]                 # closed explicitly: the last point repeats the first
    if len(points) < 4:
        read.fail("trajectory.points", table.get("points"), "at least 4 points [x, y] (mm) of a closed curve")
    check_closed_curve(points, read.fail, "trajectory.points")
    return points, kind


def check_closed_curve(points: np.ndarray, fail, field: str):
    """Refuse points that do not make a closed curve (``fail(field, value, expected)``): a point repeating the
    one before, points on one line, or a way back from the last point to the first much longer than the
    other steps (an open curve). Tolerances follow the points' own size."""
    size = np.ptp(points, axis=0).max()
    gaps = np.linalg.norm(np.diff(np.r_[points, points[:1]], axis=0), axis=1)
    if gaps[:-1].min() <= 1e-9 * size:
        k = int(np.argmin(gaps[:-1]))
        fail(f"{field}[{k + 1}]", points[k + 1].tolist(),
             f"a point distinct from points[{k}] (a repeated point makes the curve stop there)")
    spread = np.linalg.svd(points - points.mean(axis=0), compute_uv=False)
    if spread[1] <= 1e-9 * spread[0]:
        fail(field, f"{len(points)} points", "points that enclose an area (these lie on one line)")
    if gaps[-1] > OPEN_GAP_FACTOR * gaps[:-1].max():
        fail(field, f"{len(points)} points from {points[0].tolist()} to {points[-1].tolist()}",
             f"a closed curve: the way back from the last point to the first is {gaps[-1]:.1f} mm, "
             f"{gaps[-1] / gaps[:-1].max():.1f} times the longest step between the others (the curve looks "
             "open; add the points of the return stroke)")


def read_arm(read: FieldReader, table: dict):
    """[arm]: pivot (mm), the lengths (mm, or None), direction (+1 counterclockwise) and branch."""
    read.keys(table, {"pivot", "carrier_length", "arm_length", "direction", "branch"}, "arm")
    pivot = read.point(table.get("pivot", [0.0, 0.0]), "arm.pivot")
    given = [key for key in ("carrier_length", "arm_length") if key in table]
    lengths = None
    if len(given) == 1:
        read.fail(f"arm.{given[0]}", table[given[0]], "carrier_length and arm_length together, or neither "
                  "(then both come from the farthest and nearest path points, the rice-transplanter paper eq 1-2)")
    if given:
        lengths = tuple(read.length(table, key, "arm") for key in ("carrier_length", "arm_length"))
    direction = _choice(read, table, "direction", "arm", ("counterclockwise", "clockwise"), "counterclockwise")
    branch = _choice(read, table, "branch", "arm", ("auto", "approach", "retraction"), "auto")
    return pivot, lengths, 1 if direction == "counterclockwise" else -1, branch


def read_train(read: FieldReader, table: dict):
    """[train]: topology, split, peak_to_valley, center distances (mm, or None), module (mm) and cutter; its
    face_width_mm is ``read_solid_sizes``'."""
    read.keys(table, {"topology", "split", "peak_to_valley", "center_distances", "module", "cutter", "face_width_mm"},
              "train")
    topology = _choice(read, table, "topology", "train", tuple(TOPOLOGIES), "sun-intermediate-planet")
    split = _choice(read, table, "split", "train", TOPOLOGIES[topology], TOPOLOGIES[topology][0])
    if "peak_to_valley" in table and split != "peak_to_valley":
        read.fail("train.peak_to_valley", table["peak_to_valley"], f'none with split = "{split}", which does not use '
                  'it (it sets the split "peak_to_valley")')
    coefficient = read.number(table, "peak_to_valley", "train") if "peak_to_valley" in table else 0.5
    if not 0 < coefficient < 1:
        read.fail("train.peak_to_valley", coefficient, "a number in (0, 1): the share of the total ratio's swing "
                  "that stage 1 carries")
    centers: tuple[float, float] | None = None
    if "center_distances" in table:
        given = read.numbers(table, "center_distances", "train", 2)
        if len(given) != 2 or given.min() < SMALLEST_LENGTH:
            read.fail("train.center_distances", table["center_distances"], "two positive center distances (mm)")
        centers = (float(given[0]), float(given[1]))
    module = read.length(table, "module", "train") if "module" in table else 2.5
    cutter = _choice(read, table, "cutter", "train", CUTTERS, "rack")
    return topology, split, coefficient, centers, module, cutter


def parse_problem(data: dict, source: str = "<dict>") -> ReverseProblem:
    """Validate a reverse-design problem given as a dict with the fields of the file (mm).

    Parameters
    ----------
    data : dict
        The file's tables as dicts; ``trajectory.points`` may be a list, a tuple or an (N, 2) numpy array.
    source : str
        Named in error messages (the file name when read from a file).

    Returns
    -------
    ReverseProblem

    Raises
    ------
    ProblemError
        Naming the source, the field, the value and what was expected.
    """
    read = FieldReader(source)
    read.keys(data, _TOP_KEYS, "")
    if "trajectory" not in data:
        read.fail("trajectory", None, "a [trajectory] table with kind and points")
    points, kind = _trajectory_points(read, data["trajectory"])
    pivot, lengths, direction, branch = read_arm(read, data.get("arm", {}))
    topology, split, coefficient, centers, module, cutter = read_train(read, data.get("train", {}))
    return ReverseProblem(points=points - pivot, kind=kind, pivot=pivot, lengths=lengths, direction=direction,
                          branch=branch, topology=topology, split=split, peak_to_valley=coefficient,
                          center_distances=centers, module=module, cutter=cutter, source=source,
                          title=read.text(data, "title", "", LONGEST_TITLE),
                          solid_sizes=read_solid_sizes(read, data.get("train", {}), "train"),
                          tolerances=parse_tolerances(data.get("tolerances", {}), dimension_names(topology), source,
                                                      (PATH_ACCURACY_KEY,)),
                          path_accuracy_mm=read_path_accuracy(read, data.get("tolerances", {})))


def read_path_accuracy(read: FieldReader, table) -> float | None:
    """``tolerances.path_accuracy_mm``: a finite length > 0 (mm), or None where it is not given."""
    if not isinstance(table, dict) or PATH_ACCURACY_KEY not in table:
        return None
    value = table[PATH_ACCURACY_KEY]
    if not (is_finite_number(value) and 0 < value <= MAGNITUDE_LIMIT):
        read.fail(f"tolerances.{PATH_ACCURACY_KEY}", value, "a finite distance > 0 (mm) the built tip may stray "
                  "from the path")
    return float(value)

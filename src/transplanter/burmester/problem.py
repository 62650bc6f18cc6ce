"""TOML problem files (mm, degrees) -> a validated ``DyadProblem`` (mm, radians).

Schema (docs/burmester.md, "Problem files"):

    title = "..."                      # optional
    [[poses]]                          # three or more
    x = -23.1                          # mm
    y = -309.7                         # mm
    angle_deg = 113.8                  # body orientation, counterclockwise from +x
    label = "P1"                       # optional
    [relative]                         # optional: the dyad's ground is a turning link
    pivot = [0.0, 0.0]                 # mm, its fixed pivot
    phases_deg = [0, -18, -50, -90]    # its angle at each pose, counterclockwise positive
    [three_poses]                      # required with exactly three poses
    circle_points = [[x, y], ...]      # moving pivots in pose 1: find their centers
    center_points = [[x, y], ...]      # fixed pivots: find their circle points
    [search]                           # optional
    samples = 720                      # pencil directions tracing each 4-pose curve
    radius_mm = 600.0                  # keep pivots within this distance of the pose centroid

Every error names the file, the field, the value and what was expected.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from transplanter.geometry.dyad import Link
from transplanter.toml_fields import (
    LONGEST_LABEL,
    LONGEST_TITLE,
    ClassFields,
    FieldReader,
    is_sequence,
    read_toml,
    warn_if_radians,
)

#: Most poses of a least-squares problem: the search and the fit grow with their number (1000 poses: 19 s;
#: 20,000 past five minutes), and a motion sampled more finely than that gives the same dyads.
LARGEST_POSE_COUNT = 1000
_TOP_KEYS = {"title", "description", "poses", "relative", "three_poses", "search"}
_POSE_KEYS = {"x", "y", "angle_deg", "label"}
_RELATIVE_KEYS = {"pivot", "phases_deg"}
_THREE_KEYS = {"circle_points", "center_points"}
_SEARCH_KEYS = {"samples", "radius_mm"}


@dataclass(frozen=True)
class DyadProblem:
    """Poses an RR dyad must guide a body through, in mm and radians (``parse_problem`` takes degrees).

    Attributes
    ----------
    poses : ndarray, shape (n, 3)
        x, y of the body's reference point (mm) and its direction (rad, counterclockwise from
        +x, within one turn of zero); n >= 3.
    link : Link or None
        The dyad's ground when it is a link turning about ``link.pivot`` (mm) by ``link.phases``
        (rad, counterclockwise, one per pose).
    circle_points, center_points : ndarray, shape (k, 2)
        Three poses only: chosen moving pivots (pose 1) or fixed pivots, mm.
    samples : int
        Pencil directions tracing each 4-pose curve.
    radius_mm : float or None
        Keep pivots within this distance of the pose centroid (mm); None: ten pose scales.
    source, title : str
        Where the problem came from and its title.
    labels : tuple of str
        Pose names (may be empty).

    Raises
    ------
    ProblemError
        When a field has the wrong shape, a value that is not finite, or angles that look like degrees.
    """

    poses: np.ndarray
    link: Link | None = None
    circle_points: np.ndarray = field(default_factory=lambda: np.empty((0, 2)))
    center_points: np.ndarray = field(default_factory=lambda: np.empty((0, 2)))
    samples: int = 720
    radius_mm: float | None = None
    source: str = "<dict>"
    title: str = ""
    labels: tuple[str, ...] = ()

    def __post_init__(self):
        check = ClassFields(self)
        poses = check.array("poses", (None, 3), minimum=3)
        check.angles_within_a_turn("poses", poses[:, 2])
        check.array("circle_points", (None, 2))
        check.array("center_points", (None, 2))
        if self.link is not None:
            if not isinstance(self.link, Link):
                check.fail("link", self.link, "a geometry.dyad.Link (pivot, phases) or None")
            pivot, phases = _floats(self.link.pivot), _floats(self.link.phases)
            if pivot.shape != (2,) or not np.all(np.isfinite(pivot)):
                check.fail("link.pivot", self.link.pivot, "a point [x, y] of two finite numbers (mm)")
            if phases.shape != (len(poses),) or not np.all(np.isfinite(phases)):
                check.fail("link.phases", self.link.phases, f"{len(poses)} finite angles (rad), one per pose")
            check.angles_within_a_turn("link", phases)
        check.positive("radius_mm", optional=True)
        check.whole("samples", 16, 200_000)
        if not isinstance(self.labels, tuple) or (self.labels and len(self.labels) != len(poses)):
            check.fail("labels", self.labels, f"a tuple of {len(poses)} names, one per pose, or ()")
        check.text("source", "title")


def _floats(value) -> np.ndarray:
    """``value`` as a float array, or [nan] when it is not numbers."""
    try:
        return np.asarray(value, float)
    except (TypeError, ValueError):
        return np.array([np.nan])


def load_problem(path: str | Path) -> DyadProblem:
    """Read and validate a dyad problem file (TOML, mm and degrees; schema above).

    Raises
    ------
    ProblemError
        Naming the file, the field, the value and what was expected.
    """
    return parse_problem(read_toml(path), str(path))


def parse_problem(data: dict, source: str = "<dict>") -> DyadProblem:
    """Validate a dyad problem given as a dict with the fields of the file (mm, degrees).

    Parameters
    ----------
    data : dict
        The file's tables as dicts; a list of numbers may be a tuple or a numpy array.
    source : str
        Named in error messages (the file name when read from a file).

    Returns
    -------
    DyadProblem
        In mm and radians.

    Raises
    ------
    ProblemError
        Naming the source, the field, the value and what was expected.
    """
    read = FieldReader(source)
    read.keys(data, _TOP_KEYS, "")
    poses_table = read.tables(data, "poses", "an array of tables [[poses]] with x, y, angle_deg")
    if len(poses_table) < 3:
        read.fail("poses", f"{len(poses_table)} poses", "at least 3 poses")
    read.count("poses", poses_table, LARGEST_POSE_COUNT, "poses")
    rows, labels = [], []
    for k, pose in enumerate(poses_table):
        where = f"poses[{k}]"
        read.keys(pose, _POSE_KEYS, where)
        rows.append([read.number(pose, "x", where), read.number(pose, "y", where),
                     read.number(pose, "angle_deg", where)])
        labels.append(read.text(pose, "label", where, LONGEST_LABEL, f"P{k + 1}"))
    degrees = np.array(rows)
    if np.any(np.abs(degrees[:, 2]) > 360):
        read.fail("poses[].angle_deg", degrees[:, 2], "directions within one turn of zero (|angle_deg| <= 360)")
    check_distinct(read, degrees, "poses")
    warn_if_radians(source, "poses[].angle_deg", degrees[:, 2])
    poses = degrees.copy()
    poses[:, 2] = np.radians(degrees[:, 2])

    link = None
    if "relative" in data:
        relative = data["relative"]
        read.keys(relative, _RELATIVE_KEYS, "relative")
        if "pivot" not in relative or "phases_deg" not in relative:
            read.fail("relative", relative, "both pivot = [x, y] and phases_deg = [one angle per pose]")
        phases = relative["phases_deg"]
        if not is_sequence(phases) or len(phases) != len(poses):
            read.fail("relative.phases_deg", phases, f"a list of {len(poses)} angles (one per pose, degrees)")
        values = [read.number({"v": v}, "v", f"relative.phases_deg[{k}]") for k, v in enumerate(phases)]
        link = Link(read.point(relative["pivot"], "relative.pivot"), np.radians(values))

    circles = centers = np.empty((0, 2))
    if "three_poses" in data:
        three = data["three_poses"]
        read.keys(three, _THREE_KEYS, "three_poses")
        if len(poses) != 3:
            read.fail("three_poses", three, f"no such table with {len(poses)} poses (it is for exactly 3)")
        circles = read.points(three, "circle_points", "three_poses")
        centers = read.points(three, "center_points", "three_poses")
    if len(poses) == 3 and not (len(circles) or len(centers)):
        read.fail("three_poses", data.get("three_poses"),
                  "circle_points or center_points: three poses leave a two-parameter family of dyads, "
                  "so choose one pivot and the package finds the other")

    search = data.get("search", {})
    read.keys(search, _SEARCH_KEYS, "search")
    samples = read.integer(search, "samples", "search", 16, 200_000, default=720)
    radius = None
    if "radius_mm" in search:
        radius = read.number(search, "radius_mm", "search")
        if radius <= 0:
            read.fail("search.radius_mm", radius, "a positive distance (mm)")

    return DyadProblem(poses=poses, link=link, circle_points=circles, center_points=centers,
                       samples=samples, radius_mm=radius, source=source,
                       title=read.text(data, "title", "", LONGEST_TITLE), labels=tuple(labels))


def check_distinct(read: FieldReader, degrees: np.ndarray, field: str):
    """Two poses (rows x, y, angle_deg of ``field``) with the same position and orientation carry no
    information: reject them."""
    spread = max(np.ptp(degrees[:, :2], axis=0).max(), 1.0)
    for i in range(len(degrees)):
        for j in range(i + 1, len(degrees)):
            same_place = np.linalg.norm(degrees[i, :2] - degrees[j, :2]) <= 1e-9 * spread
            same_turn = abs((degrees[i, 2] - degrees[j, 2] + 180) % 360 - 180) <= 1e-9
            if same_place and same_turn:
                read.fail(f"{field}[{j}]", dict(zip(("x", "y", "angle_deg"), degrees[j, :3].tolist(), strict=True)),
                          f"a pose different from {field}[{i}] (they coincide)")

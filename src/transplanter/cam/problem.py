"""TOML cam files (mm, degrees) -> a validated ``CamProblem``.

Schema (docs/cam.md):

    title = "..."
    [cam]
    base_radius = 30.0              # mm, base circle of the profile (absent in design mode)
    direction = "counterclockwise"  # the cam's rotation, or "clockwise"
    samples = 3600                  # cam angles per turn at which everything is evaluated
    bore_radius = 8.0               # mm, for the drawings (default 0.4 of the profile's smallest radius)
    thickness_mm = 12.0             # of the disc's STEP solid (default solids.sizes' plate rule on the bore)
    [follower]
    kind = "oscillating"            # or "translating" (along +y at x = offset), or "flat_faced"
                                    # (translating along +y, its face square to the motion; no roller)
    roller_radius = 6.0             # mm
    offset = 0.0                    # translating: mm from the cam centre line
    pivot = [70.0, 0.0]             # oscillating: the arm's pivot; the cam turns about the origin
    arm_length = 58.0               # oscillating: pivot to roller centre
    roller_side = "pulled"          # oscillating: "pulled" (the cam surface drags the roller towards the
                                    # pivot: the arm in tension) or "pushed"
    [[segments]]                    # in order from cam angle 0, angles adding up to 360
    kind = "rise"                   # rise, dwell, return
    angle_deg = 110.0
    law = "harmonic"                # harmonic, cycloidal, polynomial_345, modified_trapezoid
    lift = 20.0                     # translating: mm; a return without it goes back to the base
    swing_deg = 36.0                # oscillating: degrees
    [limits]
    pressure_angle_deg = 30.0       # default 30 translating, 45 oscillating
    profile_radius_mm = 0.0         # smallest convex radius of the profile allowed (default 0: no cusp)
    [design]                        # optional: the smallest base circle meeting the limits
    max_base_radius = 200.0         # mm: the largest base circle to try (default 20 x the largest given length)
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from transplanter.solids.sizes import SolidSizes
from transplanter.toml_fields import (
    LONGEST_TITLE,
    MAGNITUDE_LIMIT,
    ClassFields,
    FieldReader,
    is_finite_number,
    is_sequence,
    read_toml,
)

LAWS = ("harmonic", "cycloidal", "polynomial_345", "modified_trapezoid")
SEGMENT_KINDS = ("rise", "dwell", "return")
#: Design mode tries base circles up to this many times the cam's largest given length (``_size``) unless
#: design.max_base_radius says otherwise: 500 mm for a 25 mm lift.
DESIGN_REACH = 20.0
DEFAULT_PRESSURE_LIMIT_DEG = {"translating": 30.0, "oscillating": 45.0, "flat_faced": 30.0}
#: Segment angles must add up to a turn within this (degrees).
TURN_TOLERANCE_DEG = 1e-6
#: Most segments of a motion program: the work grows with their number (measured in design mode on the flat-faced
#: example's turn cut into rises: 200 segments 9 s, 2000 11 s, 20,000 45 s), and a program of more is a sampled
#: motion the laws are not made for.
LARGEST_SEGMENT_COUNT = 2000
_TOO_MANY_SEGMENTS = f"at most {LARGEST_SEGMENT_COUNT} segments"
_TOP_KEYS = {"title", "description", "cam", "follower", "segments", "limits", "design"}
_CAM_KEYS = {"base_radius", "direction", "samples", "bore_radius", "thickness_mm"}
_FOLLOWER_KEYS = {"translating": {"kind", "roller_radius", "offset"}, "flat_faced": {"kind"},
                  "oscillating": {"kind", "roller_radius", "pivot", "arm_length", "roller_side"}}
_SEGMENT_KEYS = {"kind", "angle_deg", "law", "lift", "swing_deg"}


@dataclass(frozen=True)
class Segment:
    """One stretch of the motion program: ``kind`` (rise, dwell, return), ``angle`` (rad of cam),
    ``law`` (None for a dwell) and signed ``lift`` (mm, or rad of swing; negative on a return)."""

    kind: str
    angle: float
    law: str | None
    lift: float


@dataclass(frozen=True)
class Follower:
    """A roller follower, mm and radians.

    Attributes
    ----------
    kind : str
        ``"translating"`` (along +y at x = ``offset``), ``"oscillating"`` (an arm about ``pivot``) or
        ``"flat_faced"`` (translating along +y, the face square to the motion).
    roller_radius : float
        mm; 0 for the flat-faced follower.
    offset : float
        Translating: distance of the path from the cam centre line (mm).
    pivot : ndarray (2,) or None
        Oscillating: the arm's pivot (mm); the cam turns about the origin.
    arm_length : float or None
        Oscillating: pivot to roller centre (mm).
    pulled : bool
        Oscillating: the roller starts where the cam surface moves towards the pivot (arm in tension).
    """

    kind: str
    roller_radius: float
    offset: float = 0.0
    pivot: np.ndarray | None = None
    arm_length: float | None = None
    pulled: bool = True

    @property
    def arm(self) -> tuple[np.ndarray, float]:
        """(pivot, arm_length) of an oscillating follower (mm)."""
        if self.pivot is None or self.arm_length is None:
            raise TypeError(f"a {self.kind} follower has no arm")
        return self.pivot, self.arm_length


@dataclass(frozen=True)
class CamProblem:
    """A validated cam problem in mm and radians (``parse_problem`` takes mm and degrees).

    Attributes
    ----------
    base_radius : float or None
        Base circle of the profile (mm); None in design mode.
    direction : int
        +1 counterclockwise, -1 clockwise.
    follower : Follower
    segments : tuple of Segment
        From cam angle 0, adding up to a turn.
    pressure_limit : float
        Largest pressure angle allowed on rises and returns (rad).
    profile_radius_limit : float
        Smallest convex curvature radius of the profile allowed (mm; 0: any short of a cusp).
    samples : int
        Cam angles per turn.
    bore_radius : float or None
        For the drawings (mm); None: 0.4 of the profile's smallest radius.
    max_base_radius : float or None
        Design mode: the largest base circle to try (mm); None: analyse ``base_radius``.
    source, title : str
    solid_sizes : SolidSizes
        The disc's thickness for its STEP solid (``cam.thickness_mm``); None: the plate rule of ``solids.sizes`` on
        the bore's diameter.
    """

    base_radius: float | None
    direction: int
    follower: Follower
    segments: tuple[Segment, ...]
    pressure_limit: float
    profile_radius_limit: float = 0.0
    samples: int = 3600
    bore_radius: float | None = None
    max_base_radius: float | None = None
    source: str = "<dict>"
    title: str = ""
    solid_sizes: SolidSizes = field(default_factory=SolidSizes)

    def __post_init__(self):
        check = ClassFields(self)
        if not isinstance(self.solid_sizes, SolidSizes):
            check.fail("solid_sizes", self.solid_sizes, "a solids.sizes.SolidSizes")
        if (self.base_radius is None) == (self.max_base_radius is None):
            check.fail("base_radius", self.base_radius, "a positive number, or None with max_base_radius (design mode)")
        check.positive("base_radius", optional=True)
        check.positive("max_base_radius", optional=True)
        check.positive("bore_radius", optional=True)
        check.number("pressure_limit", 1e-9, np.pi / 2 - 1e-9, "an angle between 0 and pi/2 rad")
        check.number("profile_radius_limit", 0.0, MAGNITUDE_LIMIT, "a radius of 0 or more (mm)")
        check.whole("samples", 360, 100_000)
        check.choice("direction", (1, -1))
        check.text("source", "title")
        _check_follower(check, self.follower)
        _check_segments(check, self.segments, self.follower)
        total = sum(s.angle for s in self.segments)
        if abs(np.degrees(total) - 360.0) > TURN_TOLERANCE_DEG:
            check.fail("segments", f"angles adding up to {np.degrees(total):.6g} deg", "angles adding up to 2 pi")

    @property
    def oscillating(self) -> bool:
        return self.follower.kind == "oscillating"


def _check_follower(check: ClassFields, follower):
    """CamProblem.follower: a Follower of a known kind with positive sizes (mm) and, when it swings, a pivot."""
    if not isinstance(follower, Follower) or follower.kind not in _FOLLOWER_KEYS:
        check.fail("follower", follower, f"a Follower of kind {', '.join(map(repr, _FOLLOWER_KEYS))}")
    sizes: list[tuple[str, Any]] = [("roller_radius", follower.roller_radius)] if follower.kind != "flat_faced" else []
    if follower.kind == "oscillating":
        sizes.append(("arm_length", follower.arm_length))
        pivot = np.asarray(follower.pivot, float) if is_sequence(follower.pivot) else None
        if pivot is None or pivot.shape != (2,) or not np.all(np.isfinite(pivot)):
            check.fail("follower.pivot", follower.pivot, "a point [x, y] of two finite numbers (mm)")
        if not isinstance(follower.pulled, (bool, np.bool_)):
            check.fail("follower.pulled", follower.pulled, "True (pulled) or False (pushed)")
        object.__setattr__(follower, "pivot", pivot)
    for name, value in sizes:
        if not is_finite_number(value) or not 0 < value <= MAGNITUDE_LIMIT:
            check.fail(f"follower.{name}", value, "a positive length (mm)")
        object.__setattr__(follower, name, float(value))       # plain floats for the report, as the file gives
    if not is_finite_number(follower.offset):
        check.fail("follower.offset", follower.offset, "a finite distance (mm)")
    object.__setattr__(follower, "offset", float(follower.offset))


def _check_segments(check: ClassFields, segments, follower):
    """CamProblem.segments: Segments of known kinds and laws, positive angles (rad) and, for a swing, lifts
    (rad) below a half turn."""
    if not isinstance(segments, tuple) or not segments or not all(isinstance(s, Segment) for s in segments):
        check.fail("segments", segments, "a tuple of Segment")
    if len(segments) > LARGEST_SEGMENT_COUNT:
        check.fail("segments", f"{len(segments)} segments", _TOO_MANY_SEGMENTS)
    for k, segment in enumerate(segments):
        if segment.kind not in SEGMENT_KINDS or (segment.law not in LAWS) != (segment.kind == "dwell"):
            check.fail(f"segments[{k}]", segment, f"a kind of {SEGMENT_KINDS} with a law of {LAWS} (None on a dwell)")
        if not is_finite_number(segment.angle) or not 0 < segment.angle <= 2 * np.pi:
            check.fail(f"segments[{k}].angle", segment.angle, "a positive angle up to 2 pi (rad)")
        if not is_finite_number(segment.lift) or (follower.kind == "oscillating" and abs(segment.lift) >= np.pi):
            check.fail(f"segments[{k}].lift", segment.lift,
                       "a finite lift (mm), or for a swing an angle (rad) below pi")
        object.__setattr__(segment, "angle", float(segment.angle))
        object.__setattr__(segment, "lift", float(segment.lift))


def load_problem(path: str | Path) -> CamProblem:
    """Read and validate a cam file (TOML, mm and degrees; schema above).

    Raises
    ------
    ProblemError
        Naming the file, the field, the value and what was expected.
    """
    return parse_problem(read_toml(path), str(path))


def _positive(read: FieldReader, table: dict, key: str, where: str, default: float | None = None) -> float:
    if key not in table and default is not None:
        return default
    value = read.number(table, key, where)
    if value <= 0:
        read.fail(f"{where}.{key}", value, "a positive number")
    return value


def _margin(read: FieldReader, limits: dict) -> float:
    """limits.profile_radius_mm: 0 (the default) or more."""
    value = read.number(limits, "profile_radius_mm", "limits") if "profile_radius_mm" in limits else 0.0
    if value < 0:
        read.fail("limits.profile_radius_mm", value, "a radius of 0 (no cusp: the default) or more (mm)")
    return value


def _choice(read: FieldReader, table: dict, key: str, where: str, choices, default=None) -> str:
    value = table.get(key, default)
    if value not in choices:
        read.fail(f"{where}.{key}", value, "one of " + ", ".join(f'"{c}"' for c in choices))
    return value


def _size(follower: Follower, segments: tuple[Segment, ...]) -> float:
    """The cam's largest given length (mm): a translating lift, the roller, the offset, the pivot's reach."""
    lengths = [follower.roller_radius, abs(follower.offset)]
    if follower.kind == "oscillating":
        pivot, arm = follower.arm
        lengths.append(float(np.hypot(*pivot)) + arm)
    else:
        lengths += [abs(s.lift) for s in segments]
    return max(lengths)


def _follower(read: FieldReader, table) -> Follower:
    read.keys(table, set().union(*_FOLLOWER_KEYS.values()), "follower")
    kind = _choice(read, table, "kind", "follower", tuple(_FOLLOWER_KEYS))
    read.keys(table, _FOLLOWER_KEYS[kind], "follower")
    if kind == "flat_faced":
        return Follower(kind, 0.0)
    roller = _positive(read, table, "roller_radius", "follower")
    if kind == "translating":
        return Follower(kind, roller, offset=read.number(table, "offset", "follower") if "offset" in table else 0.0)
    if "pivot" not in table:
        read.fail("follower.pivot", None, "the arm's pivot [x, y] (mm) for an oscillating follower")
    pivot = read.point(table["pivot"], "follower.pivot")
    side = _choice(read, table, "roller_side", "follower", ("pulled", "pushed"), default="pulled")
    return Follower(kind, roller, pivot=pivot, arm_length=_positive(read, table, "arm_length", "follower"),
                    pulled=side == "pulled")


def _segments(read: FieldReader, data: dict, oscillating: bool) -> tuple[Segment, ...]:
    rows = read.tables(data, "segments", "an array of tables [[segments]] with kind, angle_deg, law and lift")
    if len(rows) > LARGEST_SEGMENT_COUNT:
        read.fail("segments", f"{len(rows)} segments", _TOO_MANY_SEGMENTS)
    amount_key, other_key = ("swing_deg", "lift") if oscillating else ("lift", "swing_deg")
    segments, level = [], 0.0
    for k, row in enumerate(rows):
        where = f"segments[{k}]"
        read.keys(row, _SEGMENT_KEYS, where)
        kind = _choice(read, row, "kind", where, SEGMENT_KINDS)
        angle = np.radians(_positive(read, row, "angle_deg", where))
        if other_key in row:
            follower_kind = "an oscillating" if oscillating else "a translating"
            read.fail(f"{where}.{other_key}", row[other_key], f"{amount_key} for {follower_kind} follower")
        if kind == "dwell":
            for key in ("law", amount_key):
                if key in row:
                    read.fail(f"{where}.{key}", row[key], "nothing on a dwell (it has no law and no lift)")
            segments.append(Segment(kind, angle, None, 0.0))
            continue
        law = _choice(read, row, "law", where, LAWS)
        if kind == "return" and amount_key not in row:
            amount = level
            if amount <= 0:
                read.fail(f"{where}.kind", kind, "a rise before it: the follower is at its base here")
        else:
            amount = _positive(read, row, amount_key, where)
            amount = np.radians(amount) if oscillating else amount
        if kind == "return" and amount > level * (1 + 1e-12):
            shown = np.degrees(level) if oscillating else level
            read.fail(f"{where}.{amount_key}", row[amount_key], f"at most {shown:.6g}, the height the follower is at "
                      "(a return cannot go below the base)")
        level += amount if kind == "rise" else -amount
        segments.append(Segment(kind, angle, law, amount if kind == "rise" else -amount))
    total = np.degrees(sum(s.angle for s in segments))
    if abs(total - 360.0) > TURN_TOLERANCE_DEG:
        read.fail("segments.angle_deg", f"adding up to {total:.6g}",
                  f"angles adding up to 360 (change them by {360.0 - total:+.6g} deg in all)")
    if not any(s.kind == "rise" for s in segments):
        read.fail("segments", [s.kind for s in segments], "at least one rise")
    if abs(level) > 1e-9 * max(abs(s.lift) for s in segments):
        shown = np.degrees(level) if oscillating else level
        read.fail("segments", f"ending {shown:.6g} {'deg' if oscillating else 'mm'} above the base",
                  "returns that bring the follower back to its base by the end of the turn")
    return tuple(segments)


def parse_problem(data: dict, source: str = "<dict>") -> CamProblem:
    """Validate a cam problem given as a dict with the fields of the file (mm, degrees).

    Raises
    ------
    ProblemError
        Naming the source, the field, the value and what was expected.
    """
    read = FieldReader(source)
    read.keys(data, _TOP_KEYS, "")
    for key in ("cam", "follower"):
        if key not in data:
            read.fail(key, None, f"a [{key}] table")
    cam = data["cam"]
    read.keys(cam, _CAM_KEYS, "cam")
    follower = _follower(read, data["follower"])
    segments = _segments(read, data, follower.kind == "oscillating")
    design = data.get("design")
    max_base = None
    if design is not None:
        read.keys(design, {"max_base_radius"}, "design")
        max_base = _positive(read, design, "max_base_radius", "design",
                             default=DESIGN_REACH * _size(follower, segments))
        if "base_radius" in cam:
            read.fail("cam.base_radius", cam["base_radius"], "no base radius with [design], which finds the smallest")
    base = None if design is not None else _positive(read, cam, "base_radius", "cam")
    limits = data.get("limits", {})
    read.keys(limits, {"pressure_angle_deg", "profile_radius_mm"}, "limits")
    if follower.kind == "flat_faced" and "pressure_angle_deg" in limits:
        read.fail("limits.pressure_angle_deg", limits["pressure_angle_deg"], "none for a flat-faced follower: its "
                  "face is square to its motion, so the pressure angle is 0 throughout")
    limit = _positive(read, limits, "pressure_angle_deg", "limits", default=DEFAULT_PRESSURE_LIMIT_DEG[follower.kind])
    if limit >= 90:
        read.fail("limits.pressure_angle_deg", limit, "an angle below 90 deg")
    problem = CamProblem(
        base_radius=base,
        direction={"counterclockwise": 1, "clockwise": -1}[
            _choice(read, cam, "direction", "cam", ("counterclockwise", "clockwise"), default="counterclockwise")],
        follower=follower,
        segments=segments,
        pressure_limit=np.radians(limit),
        profile_radius_limit=_margin(read, limits),
        samples=read.integer(cam, "samples", "cam", 360, 100_000, default=3600),   # 36000: 4.6 s; 1e6 ran over 5 min
        bore_radius=_positive(read, cam, "bore_radius", "cam") if "bore_radius" in cam else None,
        max_base_radius=max_base,
        source=source,
        title=read.text(data, "title", "", LONGEST_TITLE),
        solid_sizes=SolidSizes(thickness_mm=read.length(cam, "thickness_mm", "cam") if "thickness_mm" in cam else None),
    )
    if base is not None:
        check_base_radius(problem.follower, base, read.fail)
        check_swing(problem, base, read.fail)
        if problem.bore_radius is not None and problem.bore_radius >= base:
            read.fail("cam.bore_radius", problem.bore_radius, f"less than cam.base_radius = {base:g} mm (the profile "
                      "comes that near the centre)")
    return problem


def check_swing(problem: CamProblem, base_radius: float, fail):
    """Refuse an oscillating follower's swing that carries the roller past its farthest point from the cam
    centre (pivot distance + arm): there the roller moves square to the cam radius, a cam cannot turn the arm
    (pressure angle 90 deg), and beyond it the roller comes back. The roller rests at an angle b0 from the
    pivot-to-centre line (cosine rule on the base pitch circle), so the swing must stay below 180 - b0."""
    follower = problem.follower
    if follower.kind != "oscillating":
        return
    pivot, arm = follower.arm
    reach, pitch = float(np.hypot(*pivot)), base_radius + follower.roller_radius
    rest = np.arccos(np.clip((reach**2 + arm**2 - pitch**2) / (2 * reach * arm), -1.0, 1.0))
    peak = float(np.max(np.cumsum([segment.lift for segment in problem.segments])))
    if peak >= np.pi - rest:
        fail("segments.swing_deg", f"a largest swing of {np.degrees(peak):.6g}",
             f"less than {np.degrees(np.pi - rest):.6g} deg: there the roller reaches its farthest point from the "
             f"cam centre ({reach + arm:.6g} mm), where the cam cannot turn the arm")


def check_base_radius(follower: Follower, base_radius: float, fail):
    """Refuse a base circle the follower cannot sit on: ``fail(field, value, expected)``."""
    roller = follower.roller_radius
    if follower.kind == "flat_faced":
        return
    if base_radius <= roller:
        fail("follower.roller_radius", roller, f"less than the base radius {base_radius:g} mm (a roller larger than "
             "the base circle leaves no room for the bore and undercuts the profile)")
    pitch = base_radius + roller
    if follower.kind == "translating" and abs(follower.offset) >= pitch:
        fail("follower.offset", follower.offset, f"less than base radius + roller radius = {pitch:g} mm in size")
    if follower.kind == "oscillating":
        pivot, arm = follower.arm
        reach = float(np.hypot(*pivot))
        if reach <= pitch:
            fail("follower.pivot", [float(v) for v in pivot],
                 f"a pivot outside the base pitch circle (more than {pitch:g} mm from the cam centre; it is "
                 f"{reach:.6g} mm away): within it the arm turns with the cam's profile")
        low, high = abs(reach - arm), reach + arm
        if not low < pitch < high:
            fail("follower.arm_length", arm,
                 f"an arm whose roller reaches the cam: the pivot is {reach:.6g} mm from the cam centre, "
                 f"so the arm must be from {abs(reach - pitch):.6g} to {reach + pitch:.6g} mm "
                 f"to put the roller centre on the base pitch circle of radius {pitch:g} mm")

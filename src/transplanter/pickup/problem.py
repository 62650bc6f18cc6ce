"""TOML pick-up files (mm, degrees) -> a validated ``PickupProblem``.

    title = "..."
    [carrier]
    first_length = 55.0          # L1: centre O -> intermediate gear shaft O1 (stage 1 centre distance), mm
    second_length = 45.0         # L2: O1 -> planet shaft O2 (stage 2 centre distance), mm
    bend_deg = 150.0             # delta0: the carrier's bend at O1 (eq 15)
    start_deg = 0.0              # phi0: the carrier's angle at the start, counterclockwise from +x
    speed_rpm = 60.0             # the carrier turns counterclockwise
    [arm]
    length = 160.0               # S: O2 -> needle tip, mm
    mounting_deg = 30.0          # alpha0: the arm's angle on the planet, from O1 -> O2 at the start
    [stage1.driver]              # the fixed sun (gear 1); any [driver] table of a gear file
    family = "ellipse"
    ...
    [stage2.driver]              # gear 3 on O1 (fixed to gear 2), driving the planet (gear 4)
    family = "composite"
    ...
    [angles]
    picking = "farthest"         # where the needle picks: "farthest" from O, or a carrier angle in degrees
    pushing = "lowest"           # where it pushes: "lowest" tip point, or a carrier angle in degrees
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from transplanter.gears.pitch_curves import PitchCurve
from transplanter.gears.problem import FAMILIES, read_driver
from transplanter.toml_fields import (
    ANGLE_LIMIT_DEG,
    LONGEST_TITLE,
    ClassFields,
    FieldReader,
    is_finite_number,
    read_toml,
)

_STAGE_FAMILIES = tuple(f for f in FAMILIES if f != "ratio")
_CARRIER_KEYS = {"first_length", "second_length", "bend_deg", "start_deg", "speed_rpm"}
_ARM_KEYS = {"length", "mounting_deg"}


@dataclass(frozen=True)
class PickupProblem:
    """A pick-up mechanism in mm, radians and rad/s (``parse_problem`` takes mm, degrees and rpm).

    ``picking`` and ``pushing`` are "farthest" / "lowest" or a carrier turn (rad) from the start.
    """

    stages: tuple[PitchCurve, PitchCurve]
    first_length: float
    second_length: float
    bend: float
    start: float
    arm_length: float
    mounting: float
    speed: float
    picking: str | float
    pushing: str | float
    source: str
    title: str = ""

    def __post_init__(self):
        check = ClassFields(self)
        if (not isinstance(self.stages, tuple) or len(self.stages) != 2
                or not all(isinstance(stage, PitchCurve) for stage in self.stages)):
            check.fail("stages", self.stages, "a tuple of two pitch curves (gears.pitch_curves.PitchCurve)")
        for name in ("first_length", "second_length", "arm_length"):
            check.positive(name)
        for name in ("bend", "start", "mounting"):
            check.number(name, -2 * np.pi, 2 * np.pi, "an angle within one turn of zero (rad)")
        check.speed("speed")
        for name, word in (("picking", "farthest"), ("pushing", "lowest")):
            value = getattr(self, name)
            if isinstance(value, str) and value == word:
                continue
            if not is_finite_number(value) or abs(value) > np.radians(ANGLE_LIMIT_DEG):
                check.fail(name, value, f'"{word}" or a carrier turn (rad) from the start')
            object.__setattr__(self, name, float(value))
        check.text("source", "title")


def load_problem(path: str | Path) -> PickupProblem:
    """Read and validate a pick-up file (schema above); ProblemError names file, field and value."""
    return parse_problem(read_toml(path), str(path))


def _length(read, table, key, where):
    value = read.number(table, key, where)
    if value <= 0:
        read.fail(f"{where}.{key}", value, "a positive length (mm)")
    return value


def _angle(read, table, key, where, default):
    """An angle of the layout (deg in the file), within one turn."""
    if key not in table:
        return default
    value = read.number(table, key, where)
    if abs(value) > 360:
        read.fail(f"{where}.{key}", value, "an angle within one turn of zero (|angle| <= 360 deg)")
    return float(np.radians(value))


def _speed(read, table, key, where, default=60.0):
    """A turning speed (rpm); 0 would leave every speed in the report 0."""
    value = read.number(table, key, where) if key in table else default
    if value == 0:
        read.fail(f"{where}.{key}", value, "a speed other than 0 (rpm)")
    return value


def _where(read, table, key, word):
    value = table.get(key, word)
    if isinstance(value, str) and value == word:
        return word
    if not is_finite_number(value) or isinstance(value, bool) or abs(value) > ANGLE_LIMIT_DEG:
        read.fail(f"angles.{key}", value, f'"{word}" or a carrier turn in degrees from the start, within '
                                          f"±{ANGLE_LIMIT_DEG:.0e}")
    return float(np.radians(value))


def parse_problem(data: dict, source: str = "<dict>") -> PickupProblem:
    """Validate a pick-up problem given as a dict with the fields of the file (mm, degrees, rpm)."""
    read = FieldReader(source)
    read.keys(data, {"title", "description", "carrier", "arm", "stage1", "stage2", "angles"}, "")
    for name in ("carrier", "arm", "stage1", "stage2"):
        if name not in data:
            read.fail(name, None, f"a table [{name}]" + (" with a [driver] table" if name.startswith("stage") else ""))
    carrier, arm, angles = data["carrier"], data["arm"], data.get("angles", {})
    read.keys(carrier, _CARRIER_KEYS, "carrier")
    read.keys(arm, _ARM_KEYS, "arm")
    read.keys(angles, {"picking", "pushing"}, "angles")
    stages = []
    for name in ("stage1", "stage2"):
        read.keys(data[name], {"driver"}, name)
        if "driver" not in data[name]:
            read.fail(f"{name}.driver", None, "a [driver] table as in a gear file")
        stages.append(read_driver(read, data[name]["driver"], f"{name}.driver", _STAGE_FAMILIES))
    return PickupProblem(
        stages=tuple(stages), first_length=_length(read, carrier, "first_length", "carrier"),
        second_length=_length(read, carrier, "second_length", "carrier"),
        bend=_angle(read, carrier, "bend_deg", "carrier", 0.0),
        start=_angle(read, carrier, "start_deg", "carrier", 0.0),
        arm_length=_length(read, arm, "length", "arm"), mounting=_angle(read, arm, "mounting_deg", "arm", 0.0),
        speed=_speed(read, carrier, "speed_rpm", "carrier") * 2 * np.pi / 60,
        picking=_where(read, angles, "picking", "farthest"), pushing=_where(read, angles, "pushing", "lowest"),
        source=source, title=read.text(data, "title", "", LONGEST_TITLE))

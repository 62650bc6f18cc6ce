"""Key poses given as bands, and the requirements between them (Wang et al. 2025 section 3.1).

Any of a key pose's ``x``, ``y``, ``angle_deg`` and ``carrier_turn_deg`` may be a number (exact) or a band
``[low, high]``; the design NLP then chooses the pose within its band. The relative requirements of
``[requirements]`` hold between the poses the design chooses:

- ``max_offset_from_first_mm = [dx, dy]``: every other key pose within dx horizontally and dy vertically of
  the first (the paper: within 130 and 10 mm of P1);
- ``min_stroke_mm``: the horizontal distance from the first to the last key pose, in the stroke's direction,
  at least this (the paper: more than the 110-130 mm width of the seedlings' leaves);
- ``max_last_step_mm``: the horizontal step from the second-last to the last key pose, in the stroke's
  direction, at most this (the paper: P4 no more than 40 mm left of P3).

The stroke's direction is the sign of x_first - x_last at the bands' centres (+1 on Wang et al. 2025,
whose P moves towards -x while it pushes).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from transplanter.toml_fields import FieldReader, is_sequence

#: The quantities of a key pose in a file (mm, mm, deg, deg) and their rows in ``PoseBands``.
QUANTITIES = ("x", "y", "angle_deg", "carrier_turn_deg")
#: Pose sets drawn inside the bands for each one kept (those that break a requirement are drawn again).
DRAWS_PER_SET = 200


@dataclass(frozen=True)
class Requirements:
    """The relative requirements (mm; None: not required)."""

    max_offset_from_first: tuple[float, float] | None = None
    min_stroke: float | None = None
    max_last_step: float | None = None

    def rows(self, x: list, y: list, direction: float) -> list[tuple[str, Any, float, float]]:
        """(requirement name, expression, lower, upper) of every requirement on key pose coordinates
        ``x``, ``y`` (numbers or CasADi expressions, in the caller's unit, as are the limits)."""
        found: list[tuple[str, Any, float, float]] = []
        if self.max_offset_from_first is not None:
            dx, dy = self.max_offset_from_first
            for k in range(1, len(x)):
                found += [("requirements.max_offset_from_first_mm", x[k] - x[0], -dx, dx),
                          ("requirements.max_offset_from_first_mm", y[k] - y[0], -dy, dy)]
        if self.min_stroke is not None:
            found.append(("requirements.min_stroke_mm", direction * (x[0] - x[-1]), self.min_stroke, np.inf))
        if self.max_last_step is not None:
            found.append(("requirements.max_last_step_mm", direction * (x[-2] - x[-1]), -np.inf, self.max_last_step))
        return found

    def scaled(self, factor: float) -> Requirements:
        """The requirements with every length divided by ``factor`` (the NLP's unit)."""
        offset = self.max_offset_from_first
        return Requirements(None if offset is None else (offset[0] / factor, offset[1] / factor),
                            None if self.min_stroke is None else self.min_stroke / factor,
                            None if self.max_last_step is None else self.max_last_step / factor)

    def broken(self, poses: np.ndarray, direction: float, slack: float = 0.0) -> list[str]:
        """The names of the requirements a pose set (rows x, y, direction; mm) breaks by more than ``slack`` mm."""
        names = [name for name, value, low, high in self.rows(list(poses[:, 0]), list(poses[:, 1]), direction)
                 if not low - slack <= value <= high + slack]
        return list(dict.fromkeys(names))


@dataclass(frozen=True)
class PoseBands:
    """Bands of the four key poses in mm and radians: ``low`` and ``high`` of shape (4, 4), rows the poses,
    columns x, y, plate direction, carrier turn; an exact quantity has low == high."""

    low: np.ndarray
    high: np.ndarray

    @property
    def banded(self) -> np.ndarray:
        return self.high > self.low

    @property
    def centre(self) -> np.ndarray:
        return (self.low + self.high) / 2

    def field(self, labels: tuple[str, ...], pose: int, quantity: int) -> str:
        """The problem file's name of a banded quantity, as reports name its band edges."""
        return f"key_poses.{labels[pose]}.{QUANTITIES[quantity]}"

    def sample(self, rng: np.random.Generator, requirements: Requirements, direction: float) -> np.ndarray | None:
        """A pose set (4, 4) drawn uniformly inside the bands that meets the requirements, or None when
        ``DRAWS_PER_SET`` draws found none."""
        for _ in range(DRAWS_PER_SET):
            drawn = self.low + rng.random(self.low.shape) * (self.high - self.low)
            if not requirements.broken(drawn[:, :3], direction):
                return drawn
        return None

    def outside(self, chosen: np.ndarray, slack: np.ndarray) -> list[tuple[int, int]]:
        """(pose, quantity) of every chosen value (4, 4) outside its band by more than ``slack`` (per column)."""
        out = (chosen < self.low - slack) | (chosen > self.high + slack)
        return [(int(i), int(q)) for i, q in zip(*np.nonzero(out), strict=True)]


def stroke_direction(poses: np.ndarray) -> float:
    """+1 when P moves towards -x from the first key pose to the last, else -1."""
    return 1.0 if poses[0, 0] >= poses[-1, 0] else -1.0


def read_key_pose_rows(read: FieldReader, rows: list[dict]) -> tuple[np.ndarray, np.ndarray, list[str]]:
    """Low and high (n, 4) of every key pose's x, y, angle_deg, carrier_turn_deg (file units), each a number
    or a band [low, high] with low <= high, and the labels."""
    low, high, labels = [], [], []
    for k, row in enumerate(rows):
        where = f"key_poses[{k}]"
        read.keys(row, set(QUANTITIES) | {"label"}, where)
        pair = []
        for name in QUANTITIES:
            if is_sequence(row.get(name)):
                values = read.numbers(row, name, where, 2)
                if len(values) != 2 or values[0] > values[1]:
                    read.fail(f"{where}.{name}", row[name], "a number, or a band [low, high] with low <= high")
                pair.append((float(values[0]), float(values[1])))
            else:
                value = read.number(row, name, where)
                pair.append((value, value))
        low.append([p[0] for p in pair])
        high.append([p[1] for p in pair])
        labels.append(read.text(row, "label", where, 40))
    return np.array(low, float).reshape(-1, 4), np.array(high, float).reshape(-1, 4), labels


def as_given(low: np.ndarray, high: np.ndarray) -> list:
    """Values as a file gives them, for messages: a number where exact, [low, high] where a band."""
    return [float(a) if a == b else [float(a), float(b)] for a, b in zip(low, high, strict=True)]


def read_requirements(read: FieldReader, table: dict) -> Requirements:
    """The ``[requirements]`` table (mm)."""
    read.keys(table, {"max_offset_from_first_mm", "min_stroke_mm", "max_last_step_mm"}, "requirements")
    offset = None
    if "max_offset_from_first_mm" in table:
        values = read.numbers(table, "max_offset_from_first_mm", "requirements", 2)
        if len(values) != 2 or np.any(values < 0):
            read.fail("requirements.max_offset_from_first_mm", table["max_offset_from_first_mm"],
                      "[horizontal, vertical] distances >= 0 (mm) from the first key pose")
        offset = (float(values[0]), float(values[1]))
    lengths = {}
    for key in ("min_stroke_mm", "max_last_step_mm"):
        if key in table:
            lengths[key] = read.number(table, key, "requirements")
            if lengths[key] < 0:
                read.fail(f"requirements.{key}", lengths[key], "a distance >= 0 (mm)")
    return Requirements(offset, lengths.get("min_stroke_mm"), lengths.get("max_last_step_mm"))


def check_bands_meet_requirements(read: FieldReader, low: np.ndarray, high: np.ndarray,
                                  requirements: Requirements, direction: float) -> None:
    """Refuse requirements that no pose set inside the bands (file units) can meet, naming the requirement and
    the closest the bands allow."""
    def span(k: int, j: int, q: int, sign: float) -> tuple[float, float]:
        """Range of sign * (value of pose k - value of pose j) for quantity q over the bands."""
        values = (sign * (low[k, q] - high[j, q]), sign * (high[k, q] - low[j, q]))
        return min(values), max(values)

    if requirements.max_offset_from_first is not None:
        for q, limit in enumerate(requirements.max_offset_from_first):
            for k in range(1, len(low)):
                least, most = span(k, 0, q, 1.0)
                if least > limit or most < -limit:
                    read.fail("requirements.max_offset_from_first_mm", list(requirements.max_offset_from_first),
                              f"offsets the bands allow: {QUANTITIES[q]} of key pose {k + 1} lies {least:g} to "
                              f"{most:g} mm from the first's, never within {limit:g}")
    if requirements.min_stroke is not None:
        _, most = span(0, len(low) - 1, 0, direction)
        if most < requirements.min_stroke:
            read.fail("requirements.min_stroke_mm", requirements.min_stroke,
                      f"a stroke the bands allow: at most {most:g} mm from the first key pose to the last")
    if requirements.max_last_step is not None:
        least, _ = span(len(low) - 2, len(low) - 1, 0, direction)
        if least > requirements.max_last_step:
            read.fail("requirements.max_last_step_mm", requirements.max_last_step,
                      f"a last step the bands allow: at least {least:g} mm from the second-last key pose to the last")

"""Reading TOML problem files: every error names the file, the field, the value and what was expected."""
from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np

from transplanter.errors import ProblemError


def read_toml(path: str | Path) -> dict:
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError:
        raise ProblemError(f"{path}: no such file") from None
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as error:
        raise ProblemError(f"{path}: not valid TOML ({error})") from None


class FieldReader:
    """Field checks that all report through one message format."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, field: str, value, expected: str):
        raise ProblemError(f"{self.source}: {field} = {value!r}: expected {expected}")

    def keys(self, table, allowed: set[str], where: str):
        if not isinstance(table, dict):
            self.fail(where, table, "a table")
        for key in table:
            if key not in allowed:
                name = f"{where}.{key}" if where else key
                self.fail(name, table[key], f"no such field here (known: {', '.join(sorted(allowed))})")

    def number(self, table, key: str, where: str) -> float:
        field = f"{where}.{key}"
        if key not in table:
            raise ProblemError(f"{self.source}: {field} is missing: expected a number")
        value = table[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            self.fail(field, value, "a finite number")
        return float(value)

    def point(self, value, field: str) -> np.ndarray:
        if (not isinstance(value, list) or len(value) != 2
                or any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in value)):
            self.fail(field, value, "a point [x, y] of two finite numbers (mm)")
        return np.array(value, float)

    def points(self, table, key: str, where: str) -> np.ndarray:
        value = table.get(key, [])
        if not isinstance(value, list):
            self.fail(f"{where}.{key}", value, "a list of points [[x, y], ...]")
        return np.array([self.point(p, f"{where}.{key}[{k}]") for k, p in enumerate(value)]).reshape(-1, 2)

    def integer(self, table, key: str, where: str, low: int, high: int, default: int | None = None) -> int:
        field = f"{where}.{key}" if where else key
        if key not in table:
            if default is None:
                raise ProblemError(f"{self.source}: {field} is missing: expected a whole number from {low} to {high}")
            return default
        value = table[key]
        if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
            self.fail(field, value, f"a whole number from {low} to {high}")
        return value

    def numbers(self, table, key: str, where: str, minimum_count: int = 1) -> np.ndarray:
        field = f"{where}.{key}"
        value = table.get(key)
        if (not isinstance(value, list) or len(value) < minimum_count
                or any(isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) for v in value)):
            self.fail(field, value, f"a list of at least {minimum_count} finite numbers")
        return np.array(value, float)

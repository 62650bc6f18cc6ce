"""Reading problems from TOML files or from dicts built in Python: every error names the source,
the field, the value and what was expected.

A dict may hold what TOML would (lists of numbers, tables) or what a script has at hand: a
tuple or a numpy array wherever a list of numbers goes, numpy integers and floats wherever a
number goes. The checks and messages are the same either way.
"""
from __future__ import annotations

import math
import numbers
import os
import stat
import tomllib
import warnings
from pathlib import Path
from typing import NoReturn, TypeGuard

import numpy as np

from transplanter.errors import ProblemError, TransplanterWarning
from transplanter.toml_nesting import nesting_depth

#: Largest magnitude a number of a problem may have: lengths and coordinates in mm (a kilometre
#: of mechanism and more), counts, ratios and speeds. Beyond it squares and sums of squares of
#: the lengths lose the digits the checks need, and soon overflow.
MAGNITUDE_LIMIT = 1e9
#: Smallest length a problem may give (mm): below it, products and quotients of lengths underflow.
SMALLEST_LENGTH = 1 / MAGNITUDE_LIMIT
#: Largest magnitude of an angle in degrees (fields named ``*_deg``): ten thousand turns and more;
#: beyond it an angle's fraction of a turn has lost its digits.
ANGLE_LIMIT_DEG = 1e6


def _limit(field: str) -> float:
    return ANGLE_LIMIT_DEG if "_deg" in field else MAGNITUDE_LIMIT


def _within(value, field: str) -> bool:
    return is_finite_number(value) and abs(value) <= _limit(field)


def _finite_expected(field: str) -> str:
    unit = "deg" if "_deg" in field else "mm for a length"
    return f"a finite number within ±{_limit(field):.0e} ({unit}; beyond it the numerics lose the digits they need)"


def warn_if_radians(source: str, field: str, angles_deg: np.ndarray):
    """A TransplanterWarning when degree fields ``angles_deg`` that differ all lie within ±2 pi: radians, likely."""
    if np.abs(angles_deg).max() <= 2 * np.pi and np.ptp(angles_deg) > 0:
        warnings.warn(f"{source}: {field} are all within ±{2 * np.pi:.2f}: these look like radians, but the field "
                      "is in degrees", TransplanterWarning, stacklevel=3)


#: Largest problem file read (bytes): the bundled examples are a few kB; a design study's file a few hundred.
LARGEST_FILE = 16 * 2**20
#: Deepest nesting of arrays and inline tables a problem file may have (the bundled examples nest two deep).
DEEPEST_NESTING = 64


def read_toml(path: str | Path) -> dict:
    """The content of the TOML file at ``path``: a regular file (not a FIFO or a device, which could block
    or never end) of at most ``LARGEST_FILE`` bytes, nested at most ``DEEPEST_NESTING`` deep.

    Raises
    ------
    ProblemError
        When ``path`` is not a file name, the file is missing, unreadable, not a regular file, too large,
        nested too deeply, or not valid TOML.
    """
    if not isinstance(path, (str, os.PathLike)) or not str(path):
        raise ProblemError(f"path = {shown(path)}: expected the name of a TOML problem file (str or Path)")
    path = Path(path)
    name = shown_name(path)
    try:
        kind = os.stat(path).st_mode
        if not stat.S_ISREG(kind):
            raise ProblemError(f"{name}: {_KINDS.get(stat.S_IFMT(kind), 'not a regular file')}; expected a TOML "
                               "problem file")
        with path.open("rb") as handle:
            content = handle.read(LARGEST_FILE + 1)
        if len(content) > LARGEST_FILE:
            raise ProblemError(f"{name}: larger than {LARGEST_FILE // 2**20} MB; expected a TOML problem file "
                               "of at most that size")
        text = content.decode()
    except FileNotFoundError:
        raise ProblemError(f"{name}: no such file") from None
    except OSError as error:
        raise ProblemError(f"{name}: cannot be read ({error.strerror}): expected a TOML problem file") from None
    except UnicodeDecodeError as error:
        raise ProblemError(f"{name}: not valid TOML ({error})") from None
    if (depth := nesting_depth(text)) > DEEPEST_NESTING:
        raise ProblemError(f"{name}: arrays or tables nested {depth} deep; expected at most {DEEPEST_NESTING}")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ProblemError(f"{name}: not valid TOML ({error})") from None


_KINDS = {stat.S_IFDIR: "a folder", stat.S_IFIFO: "a FIFO (named pipe)", stat.S_IFCHR: "a character device",
          stat.S_IFBLK: "a block device", stat.S_IFSOCK: "a socket"}


def shown_name(path: str | Path) -> str:
    """A file name as a message shows it: as it is, or quoted with its escapes where it holds a line break or
    another character that is not printed (a message stays one line)."""
    text = str(path)
    return text if text.isprintable() else repr(text)


#: Longest text a message quotes in full; longer values are cut and their length given.
SHOWN_LENGTH = 300


class _Cut(str):
    """A long value as a message shows it: its start, and how long it is."""

    def __repr__(self):
        return self


def shown(value):
    """``value`` as a message shows it: numpy arrays and scalars as the plain lists and numbers TOML
    gives, and a value longer than ``SHOWN_LENGTH`` characters cut to its start and its length."""
    if isinstance(value, (np.ndarray, np.generic)):
        value = value.tolist()
    text = repr(value)
    if len(text) > SHOWN_LENGTH:
        return _Cut(f"{text[:SHOWN_LENGTH - 20]}... ({len(text)} characters)")
    return value


def is_number(value) -> bool:
    """A real number (Python or numpy, integer or float) that is not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def is_finite_number(value) -> bool:
    """A real number within the floats' range (10**400, an integer TOML and Python allow, is not)."""
    try:
        return is_number(value) and math.isfinite(value)
    except OverflowError:
        return False


def is_sequence(value) -> TypeGuard[list | tuple | np.ndarray]:
    """A list, a tuple or a numpy array of at least one dimension."""
    return isinstance(value, (list, tuple)) or (isinstance(value, np.ndarray) and value.ndim >= 1)


#: Longest title and label read: a title heads the figures and reports, a label marks a point in a figure.
LONGEST_TITLE, LONGEST_LABEL = 200, 40


class FieldReader:
    """Field checks that all report through one message format."""

    def __init__(self, source: str):
        self.source = source

    def fail(self, field: str, value, expected: str) -> NoReturn:
        raise ProblemError(f"{self.source}: {field} = {shown(value)!r}: expected {expected}")

    def keys(self, table, allowed: set[str], where: str):
        """Refuse a ``table`` that is not a dict, or that has a key outside ``allowed``."""
        if not isinstance(table, dict):
            if where:
                self.fail(where, table, "a table")
            self.fail("problem", table, "a table of fields (a dict, as a TOML file gives)")
        for key in table:
            if key not in allowed:
                name = f"{where}.{key}" if where else key
                self.fail(name, table[key], f"no such field here (known: {', '.join(sorted(allowed))})")

    def text(self, table: dict, key: str, where: str, longest: int, default: str = "") -> str:
        """A line of text (a title, a label): a string of at most ``longest`` characters without control
        characters (figures draw it, reports print it)."""
        value = table.get(key, default)
        if not isinstance(value, str) or len(value) > longest or any(ord(c) < 32 or ord(c) == 127 for c in value):
            field = f"{where}.{key}" if where else key
            self.fail(field, value if not isinstance(value, str) or len(value) <= 60 else value[:60] + "...",
                      f"text of at most {longest} characters on one line, without control characters")
        return value

    def tables(self, data: dict, key: str, expected: str) -> list[dict]:
        """The array of tables ``data[key]`` (a list or tuple of dicts)."""
        rows = data.get(key)
        if not isinstance(rows, (list, tuple)) or not all(isinstance(r, dict) for r in rows):
            self.fail(key, rows, expected)
        return list(rows)

    def number(self, table, key: str, where: str) -> float:
        field = f"{where}.{key}"
        if key not in table:
            raise ProblemError(f"{self.source}: {field} is missing: expected a number")
        value = table[key]
        if not _within(value, field):
            self.fail(field, value, _finite_expected(field))
        return float(value)

    def length(self, table, key: str, where: str) -> float:
        """A positive length (mm) from ``SMALLEST_LENGTH`` to ``MAGNITUDE_LIMIT``."""
        value = self.number(table, key, where)
        if not SMALLEST_LENGTH <= value <= MAGNITUDE_LIMIT:
            self.fail(f"{where}.{key}", value,
                      f"a positive length from {SMALLEST_LENGTH:.0e} to {MAGNITUDE_LIMIT:.0e} mm")
        return value

    def point(self, value, field: str) -> np.ndarray:
        if not is_sequence(value) or len(value) != 2 or not all(_within(v, field) for v in value):
            self.fail(field, value, f"a point [x, y] of two finite numbers (mm) within ±{MAGNITUDE_LIMIT:.0e}")
        return np.array(value, float)

    def points(self, table, key: str, where: str, largest: int | None = None) -> np.ndarray:
        value = table.get(key, [])
        if not is_sequence(value):
            self.fail(f"{where}.{key}", value, "a list of points [[x, y], ...]")
        self.count(f"{where}.{key}", value, largest, "points")
        return np.array([self.point(p, f"{where}.{key}[{k}]") for k, p in enumerate(value)]).reshape(-1, 2)

    def integer(self, table, key: str, where: str, low: int, high: int, default: int | None = None) -> int:
        field = f"{where}.{key}" if where else key
        if key not in table:
            if default is None:
                raise ProblemError(f"{self.source}: {field} is missing: expected a whole number from {low} to {high}")
            return default
        value = table[key]
        if not is_number(value) or not isinstance(value, numbers.Integral) or not low <= int(value) <= high:
            self.fail(field, value, f"a whole number from {low} to {high}")
        return int(value)

    def count(self, field: str, value, largest: int | None, what: str):
        """Refuse a list ``value`` of more than ``largest`` items (None: no cap), before its items are read: the
        work that follows grows with their number."""
        if largest is not None and is_sequence(value) and len(value) > largest:
            self.fail(field, f"{len(value)} {what}", f"at most {largest} {what} (the cap on this list's size)")

    def numbers(self, table, key: str, where: str, minimum_count: int = 1, largest: int | None = None) -> np.ndarray:
        field = f"{where}.{key}"
        value = table.get(key)
        self.count(field, value, largest, "numbers")
        if not is_sequence(value) or len(value) < minimum_count or not all(_within(v, field) for v in value):
            self.fail(field, value, f"a list of at least {minimum_count} finite numbers within ±{_limit(field):.0e}")
        return np.array(value, float)

    def flag(self, table, key: str, where: str, default: bool) -> bool:
        value = table.get(key, default)
        if not isinstance(value, (bool, np.bool_)):
            self.fail(f"{where}.{key}", value, "true or false")
        return bool(value)


class ClassFields:
    """Checks of a problem class built directly in Python (mm, radians): each failure names the
    class, the field and the value, and says which units the class and ``parse_problem`` take."""

    def __init__(self, problem):
        self.problem = problem
        self.owner = type(problem).__name__

    def fail(self, field: str, value, expected: str) -> NoReturn:
        raise ProblemError(f"{self.owner}.{field} = {shown(value)!r}: expected {expected} ({self.owner} takes mm "
                           "and radians; parse_problem and load_problem take the file's mm and degrees)")

    def array(self, field: str, shape: tuple[int | None, ...], minimum: int = 0) -> np.ndarray:
        """The field as a float array of ``shape`` (None: any length, at least ``minimum``) with
        finite values; stored back on the (frozen) problem."""
        value = getattr(self.problem, field)
        sizes = ", ".join("m" if n is None else str(n) for n in shape) + ("," if len(shape) == 1 else "")
        expected = f"an array of numbers of shape ({sizes})" + (f" with m >= {minimum}" if minimum else "")
        try:
            array = np.array(value, float)
        except (TypeError, ValueError):
            self.fail(field, value, expected)
        if (array.ndim != len(shape)
                or any(n is not None and n != size for n, size in zip(shape, array.shape, strict=True))
                or any(n is None and size < minimum for n, size in zip(shape, array.shape, strict=True))):
            self.fail(field, value, expected)
        if not np.all(np.isfinite(array)) or np.any(np.abs(array) > MAGNITUDE_LIMIT):
            self.fail(field, value, f"finite values within ±{MAGNITUDE_LIMIT:.0e}")
        object.__setattr__(self.problem, field, array)
        return array

    def angles_within_a_turn(self, field: str, angles: np.ndarray):
        if np.any(np.abs(angles) > 2 * np.pi):
            self.fail(field, getattr(self.problem, field), "angles within one turn of zero (|angle| <= 2 pi rad)")

    def positive(self, field: str, optional: bool = False):
        """A positive number up to ``MAGNITUDE_LIMIT``, stored back as a float."""
        value = getattr(self.problem, field)
        if optional and value is None:
            return
        if not is_finite_number(value) or not 0 < value <= MAGNITUDE_LIMIT:
            self.fail(field, value, f"a positive number up to {MAGNITUDE_LIMIT:.0e}" + (" or None" if optional else ""))
        object.__setattr__(self.problem, field, float(value))

    def number(self, field: str, low: float, high: float, expected: str):
        """A number in [low, high] (``expected`` says so in words), stored back as a float."""
        value = getattr(self.problem, field)
        if not is_finite_number(value) or not low <= value <= high:
            self.fail(field, value, expected)
        object.__setattr__(self.problem, field, float(value))

    def speed(self, field: str):
        """A turning speed (rad/s) other than 0 (every speed of the report would be 0), stored back as a float."""
        self.number(field, -MAGNITUDE_LIMIT, MAGNITUDE_LIMIT, "a finite speed (rad/s) other than 0")
        if getattr(self.problem, field) == 0:
            self.fail(field, 0.0, "a speed other than 0 (rad/s)")

    def whole(self, field: str, low: int, high: int, optional: bool = False):
        """A whole number from ``low`` to ``high`` (not a bool), stored back as an int."""
        value = getattr(self.problem, field)
        if optional and value is None:
            return
        if not is_number(value) or not isinstance(value, numbers.Integral) or not low <= int(value) <= high:
            self.fail(field, value, f"a whole number from {low} to {high}" + (" or None" if optional else ""))
        object.__setattr__(self.problem, field, int(value))

    def choice(self, field: str, options):
        """One of ``options`` (text, or numbers of any kind but bool), stored back as that option."""
        value = getattr(self.problem, field)
        if not isinstance(value, (str, numbers.Real)) or isinstance(value, (bool, np.bool_)) or value not in options:
            self.fail(field, value, "one of " + ", ".join(repr(option) for option in options))
        object.__setattr__(self.problem, field, options[options.index(value)])

    def text(self, *fields: str):
        """Text fields (a source may be a Path), stored back as str."""
        for field in fields:
            value = getattr(self.problem, field)
            if not isinstance(value, (str, os.PathLike)):
                self.fail(field, value, "text")
            object.__setattr__(self.problem, field, str(value))

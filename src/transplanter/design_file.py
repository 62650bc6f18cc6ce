"""design.toml: the design a run made, written into ``--out`` so that ``--design`` reads it back.

The file uses the names of the report's design table (report.json) and writes every float with ``repr``
(the shortest text that reads back to the same double), so the design it holds is the run's, bit for bit.
A design file written before the names were unified may use an older name: ``renamed_fields`` reads it
with a one-line note naming the new name.
"""
from __future__ import annotations

import json
import math
import numbers
import warnings
from collections.abc import Mapping
from pathlib import Path

from transplanter.errors import TransplanterWarning
from transplanter.toml_fields import FieldReader, read_toml

DESIGN_FILE = "design.toml"


def _value(value) -> str:
    """One TOML value: a real number as the ``repr`` of its float, an integer, a bool, a string, or an array of
    these (numpy's numbers and arrays included)."""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, numbers.Integral):
        return str(int(value))
    if isinstance(value, numbers.Real):
        if not math.isfinite(value):
            raise ValueError(f"a design file holds finite numbers only, not {value!r}")
        return repr(float(value))
    if isinstance(value, str):
        return json.dumps(value)        # a JSON string is a TOML basic string
    return "[" + ", ".join(_value(item) for item in value) + "]"


def design_toml(title: str, description: str, tables: Mapping[str, Mapping[str, object]]) -> str:
    """The text of a design file: a title, a description and one TOML table per entry of ``tables``."""
    lines = [f"title = {_value(title)}", f"description = {_value(description)}"]
    for name, table in tables.items():
        lines += ["", f"[{name}]", *(f"{key} = {_value(value)}" for key, value in table.items())]
    return "\n".join(lines) + "\n"


def write_design_file(folder: str | Path, title: str, description: str,
                      tables: Mapping[str, Mapping[str, object]]) -> Path:
    """Write ``design_toml(...)`` as ``folder/design.toml`` (the folder made if missing); the path written."""
    path = Path(folder) / DESIGN_FILE
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(design_toml(title, description, tables))
    return path


def renamed_fields(read: FieldReader, table: dict, where: str, renamed: Mapping[str, str]) -> dict:
    """``table`` with each older name of ``renamed`` (old -> new) read as its new name, with a one-line
    ``TransplanterWarning`` per older name; both names at once is refused."""
    table = dict(table)
    for old, new in renamed.items():
        if old not in table:
            continue
        if new in table:
            read.fail(f"{where}.{old}", table[old], f"only {new} (its new name), which is also given")
        warnings.warn(f"{read.source}: {where}.{old} is now named {new} (the report's name); the old name "
                      "will be refused in a later version", TransplanterWarning, stacklevel=2)
        table[new] = table.pop(old)
    return table


def read_design_file(path: str | Path, tables: set[str], main: str, fields: set[str]) -> tuple[dict, dict, FieldReader]:
    """A design file's content, its table ``main`` and a reader of its fields, after refusing (ProblemError naming
    the file, the field, the value and what was expected) a top-level key other than title, description and
    ``tables``, and a field of ``main`` outside ``fields``."""
    data = read_toml(path)
    read = FieldReader(str(path))
    read.keys(data, {"title", "description", *tables}, "")
    table = data.get(main)
    read.keys(table, fields, main)
    assert isinstance(table, dict)      # read.keys refuses anything else
    return data, table, read

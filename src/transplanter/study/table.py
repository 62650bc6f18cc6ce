"""cases.csv: one row per finished case, appended (and flushed to disk) as the case finishes.

Columns: case_id, status, exit_class, binding, error, seconds, attempts, the varied fields, the collected
quantities. Numbers are written exactly (``repr``), so a table read back gives the same floats.
"""
from __future__ import annotations

import csv
import io
import json
import math
import os
from pathlib import Path
from typing import Any

import numpy as np

from transplanter.output_folder import staged_file
from transplanter.study.field_paths import MISSING, read

#: The columns every table starts with.
CASE_COLUMNS = ("case_id", "status", "exit_class", "binding", "error", "seconds", "attempts")


def columns(fields: tuple[str, ...], collect: tuple[str, ...]) -> list[str]:
    """The table's header."""
    return [*CASE_COLUMNS, *fields, *collect]


def cell(value: Any) -> str:
    """A value as the table writes it: numbers exactly, None and missing values empty, arrays as JSON."""
    if value is None or value is MISSING:
        return ""
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        return repr(value)
    if isinstance(value, (dict, list, tuple)):
        return json.dumps(value, separators=(",", ":"))
    return str(value)


def row_of(case_id: str, values: dict[str, Any], outcome: dict[str, Any], attempts: int,
           collect: tuple[str, ...]) -> dict[str, str]:
    """The row of a finished case: its outcome (``case_run.run_case``'s, or a timeout or crash) and the
    collected quantities read from its report."""
    report = outcome.get("report", {})
    return {"case_id": case_id, **{key: cell(outcome.get(key)) for key in CASE_COLUMNS[1:-1]},
            "attempts": str(attempts), **{name: cell(value) for name, value in values.items()},
            **{path: cell(read(report, path)) for path in collect}}


def append_row(path: Path, header: list[str], row: dict[str, str]):
    """Append ``row`` to the table at ``path`` (with the header when the table is new), on disk when it returns."""
    new = not path.exists()
    text = io.StringIO()
    writer = csv.DictWriter(text, header, lineterminator="\n")
    if new:
        writer.writeheader()
    writer.writerow(row)
    with path.open("a", newline="") as stream:
        stream.write(text.getvalue())
        stream.flush()
        os.fsync(stream.fileno())


def read_rows(path: Path, header: list[str]) -> list[dict[str, str]]:
    """The whole rows of the table at ``path`` (none when missing); a last row cut short by a kill is dropped,
    and the file rewritten without it."""
    if not path.exists():
        return []
    with path.open(newline="") as stream:
        lines = stream.read()
    whole = lines.endswith("\n")
    rows = list(csv.reader(io.StringIO(lines)))
    if rows and rows[0] != header:
        return []
    kept = [dict(zip(header, r, strict=True)) for r in rows[1:] if len(r) == len(header)]
    if not whole or len(kept) != len(rows) - 1:
        with staged_file(path) as partial:
            text = io.StringIO()
            writer = csv.DictWriter(text, header, lineterminator="\n")
            writer.writeheader()
            writer.writerows(kept[:-1] if not whole and len(kept) == len(rows) - 1 else kept)
            partial.write_text(text.getvalue())
        return read_rows(path, header)
    return kept


def number(text: str) -> float:
    """A cell as a float, NaN when it is empty or not a number."""
    try:
        return float(text)
    except ValueError:
        return math.nan


def numeric_column(rows: list[dict[str, str]], column: str) -> np.ndarray:
    """A column of ``rows`` as floats, NaN where a cell is empty or not a number."""
    return np.array([number(row[column]) for row in rows], float)

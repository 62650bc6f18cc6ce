"""Small studies the study tests share: gear pairs (a few seconds each), some of which undercut."""
from __future__ import annotations

import math
from pathlib import Path

from transplanter.study import parse_study

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


def gear_study_data(**changes) -> dict:
    """Four focal-ellipse pairs: eccentricity 0.3 or 0.8 (which undercuts at module 2), 30 or 40 teeth."""
    return {"title": "Ellipse pairs", "command": "gear", "problem": str(EXAMPLES / "gear_ellipse.toml"),
            "collect": ["center_distance", "closure_error", "ratio_range.1"],
            "vary": [{"field": "driver.eccentricity", "values": [0.3, 0.8]},
                     {"field": "pair.teeth", "range": [30, 40], "step": 10}],
            "executor": {"workers": 2}, **changes}


def gear_study(**changes):
    return parse_study(gear_study_data(**changes), "<gear study>")


def same_tables(first: list[dict], second: list[dict], tolerance: float = 1e-9) -> bool:
    """Whether two tables hold the same cases with the same statuses, errors and values (numbers to
    ``tolerance`` relative), in any order; the seconds and attempts may differ."""
    by_id = {row["case_id"]: row for row in second}
    if sorted(by_id) != sorted(row["case_id"] for row in first) or len(by_id) != len(second):
        return False
    for row in first:
        other = by_id[row["case_id"]]
        for column, value in row.items():
            if column in ("seconds", "attempts"):
                continue
            try:
                a, b = float(value), float(other[column])
            except ValueError:
                if value != other[column]:
                    return False
            else:
                if not math.isclose(a, b, rel_tol=tolerance, abs_tol=tolerance):
                    return False
    return True

"""cases.csv: rows written exactly, read back whole, a row cut short by a kill dropped."""
from __future__ import annotations

import numpy as np

from transplanter.study.pareto import pareto_front
from transplanter.study.table import append_row, columns, numeric_column, read_rows, row_of

HEADER = columns(("a.x",), ("q", "r.0"))


def _row(case_id: str, x: float) -> dict[str, str]:
    outcome = {"status": "passed", "exit_class": 0, "error": "", "binding": "", "seconds": 0.5,
               "report": {"q": x / 3, "r": [True, 2]}}
    return row_of(case_id, {"a.x": x}, outcome, 1, ("q", "r.0"))


def test_rows_are_read_back_with_the_same_floats(tmp_path):
    path = tmp_path / "cases.csv"
    for k, x in enumerate([0.1, 1 / 7, -2e-300]):
        append_row(path, HEADER, _row(f"id{k}", x))
    rows = read_rows(path, HEADER)
    assert [row["case_id"] for row in rows] == ["id0", "id1", "id2"]
    assert numeric_column(rows, "q").tolist() == [0.1 / 3, 1 / 7 / 3, -2e-300 / 3]
    assert [row["r.0"] for row in rows] == ["true"] * 3


def test_a_row_cut_short_by_a_kill_is_dropped_and_the_table_rewritten(tmp_path):
    path = tmp_path / "cases.csv"
    for k in range(2):
        append_row(path, HEADER, _row(f"id{k}", float(k)))
    whole = path.read_text()
    path.write_text(whole + whole.splitlines()[-1][:-7])       # a third row, its end not written
    assert [row["case_id"] for row in read_rows(path, HEADER)] == ["id0", "id1"]
    assert path.read_text() == whole


def test_the_pareto_front_is_the_set_no_point_dominates(rng):
    points = rng.normal(size=(60, 2))
    points[5] = np.nan
    goals = ["min", "max"]
    front = set(pareto_front(points, goals).tolist())
    costs = points * [1, -1]
    for k, cost in enumerate(costs):
        dominated = any(np.all(other <= cost) and np.any(other < cost) for other in costs if np.isfinite(other).all())
        assert (k in front) == (np.isfinite(cost).all() and not dominated)

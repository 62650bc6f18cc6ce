"""The study's figures: where the requirements can be met (which one binds, by colour) over each pair of varied
fields, the collected quantities over the sweep, and the Pareto front of two objectives."""
from __future__ import annotations

import itertools
import textwrap

import numpy as np
from matplotlib.figure import Figure

from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE
from transplanter.study.case_run import PASSED
from transplanter.study.pareto import pareto_front
from transplanter.study.spec import StudySpec
from transplanter.study.table import numeric_column

#: Units by the end of a field's name; x and y of a point are mm, other names are given as they are.
_UNITS = (("_deg", "deg"), ("_mm", "mm"), ("_s", "s"), ("_rpm", "rpm"), ("_rad_s", "rad/s"))
_MILLIMETRES = {"x", "y", "module"}


def axis_label(path: str) -> str:
    """A field or quantity with its unit: from the name's ending (``_deg``, ``_mm``...; an array's entry has its
    array's), mm for coordinates and lengths, "1" for a count or ratio."""
    name = [part for part in path.split(".") if not part.isdigit()][-1]
    unit = next((u for end, u in _UNITS if name.endswith(end)), None)
    if unit is None:
        unit = "mm" if name in _MILLIMETRES or "length" in name else "1"
    return f"{path} ({unit})"


def _category(row: dict[str, str]) -> str:
    return "passed" if row["status"] == PASSED else row["binding"] or row["status"]


def _titled(figure: Figure, spec: StudySpec, what: str):
    """The study's title (wrapped) over the figure, and what the figure shows under it."""
    figure.suptitle(textwrap.fill(spec.title, 90) + "\n" + what, **PROBLEM_TITLE)


def feasibility_map(spec: StudySpec, rows: list[dict[str, str]], first: str, second: str | None) -> Figure:
    """Cases over two varied fields (or one, against the binding requirement), coloured by the requirement that
    binds: "passed" where every check passes."""
    figure = Figure(figsize=(8.5, 5), layout="constrained")
    axes = figure.add_subplot()
    categories = sorted({_category(row) for row in rows}, key=lambda c: (c != "passed", c))
    x = numeric_column(rows, first)
    y = numeric_column(rows, second) if second else np.array([categories.index(_category(r)) for r in rows], float)
    colours = dict(zip(categories, itertools.cycle([f"C{k}" for k in range(10)]), strict=False))
    for category in categories:
        mine = np.array([_category(row) == category for row in rows])
        axes.scatter(x[mine], y[mine], s=40, color=colours[category], marker="o" if category == "passed" else "x",
                     label=category)
    axes.set_xlabel(axis_label(first))
    if second:
        axes.set_ylabel(axis_label(second))
    else:
        axes.set_yticks(range(len(categories)), categories)
        axes.set_ylabel("what binds")
    _titled(figure, spec, "feasibility, by what binds")
    axes.legend(title="what binds", fontsize="small", **LEGEND_BESIDE)
    return figure


def quantities_over_sweep(spec: StudySpec, rows: list[dict[str, str]], quantities: list[str]) -> Figure:
    """Each numeric collected quantity against each varied field: passed cases filled, the others hollow."""
    fields = [f for f in spec.fields if np.isfinite(numeric_column(rows, f)).any()]
    figure = Figure(figsize=(3.2 * len(fields) + 2, 2.6 * len(quantities) + 0.6), layout="constrained")
    passed = np.array([row["status"] == PASSED for row in rows])
    grid = figure.subplots(len(quantities), len(fields), squeeze=False)
    for (i, quantity), (j, field) in itertools.product(enumerate(quantities), enumerate(fields)):
        axes = grid[i][j]
        x, y = numeric_column(rows, field), numeric_column(rows, quantity)
        axes.scatter(x[passed], y[passed], s=24, color="C0", label="passed")
        axes.scatter(x[~passed], y[~passed], s=24, facecolors="none", edgecolors="C3", label="not passed")
        axes.set_xlabel(axis_label(field))
        axes.set_ylabel(axis_label(quantity))
    grid[0][-1].legend(**LEGEND_BESIDE)
    _titled(figure, spec, "collected quantities over the sweep")
    return figure


def pareto_figure(spec: StudySpec, rows: list[dict[str, str]]) -> Figure:
    """The passed cases in the plane of the two objectives, the non-dominated ones joined."""
    first, second = spec.objectives
    figure = Figure(figsize=(7.5, 5), layout="constrained")
    axes = figure.add_subplot()
    passed = [row for row in rows if row["status"] == PASSED]
    x, y = numeric_column(passed, first.quantity), numeric_column(passed, second.quantity)
    front = pareto_front(np.column_stack([x, y]), [first.goal, second.goal])
    axes.scatter(x, y, s=24, color="C7", label="passed cases")
    order = front[np.argsort(x[front])]
    axes.plot(x[order], y[order], "o-", color="C1", label="Pareto front")
    axes.set_xlabel(f"{axis_label(first.quantity)}, {first.goal}imised")
    axes.set_ylabel(f"{axis_label(second.quantity)}, {second.goal}imised")
    _titled(figure, spec, "Pareto front")
    axes.legend(**LEGEND_BESIDE)
    return figure


def draw_figures(spec: StudySpec, rows: list[dict[str, str]]) -> dict[str, Figure]:
    """The figures by file stem: a feasibility map per pair of numeric varied fields (one map for a single
    field), the quantities over the sweep, and the Pareto front when the study names two objectives."""
    if not rows:
        return {}
    fields = [f for f in spec.fields if np.isfinite(numeric_column(rows, f)).any()]
    pairs: list[tuple[str, str | None]] = list(itertools.combinations(fields, 2)) or [(f, None) for f in fields]
    figures = {f"feasibility_{k + 1}" if len(pairs) > 1 else "feasibility": feasibility_map(spec, rows, a, b)
               for k, (a, b) in enumerate(pairs)}
    quantities = [q for q in spec.collect if np.isfinite(numeric_column(rows, q)).any()]
    if quantities and fields:
        figures["quantities"] = quantities_over_sweep(spec, rows, quantities)
    if spec.objectives and any(row["status"] == PASSED for row in rows):
        figures["pareto"] = pareto_figure(spec, rows)
    return figures

"""The study's report (report.md, report.json) and figures, written when its cases are done: the best cases
and the failure classes."""
from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np

from transplanter.output_folder import files_by_kind, report_json, staged_file
from transplanter.study.case_run import PASSED
from transplanter.study.figures import draw_figures
from transplanter.study.folder import STUDY_FILE, study_hash
from transplanter.study.pareto import pareto_front
from transplanter.study.spec import StudySpec
from transplanter.study.table import numeric_column

#: How many best cases the report lists.
BEST_LISTED = 10


def best_cases(spec: StudySpec, rows: list[dict[str, str]]) -> list[dict[str, str]]:
    """The passed cases worth a look: the Pareto front of the two objectives (by the first), or else the
    passed cases in the table's order; at most ``BEST_LISTED``."""
    passed = [row for row in rows if row["status"] == PASSED]
    if spec.objectives and passed:
        points = np.column_stack([numeric_column(passed, o.quantity) for o in spec.objectives])
        front = pareto_front(points, [o.goal for o in spec.objectives])
        passed = [passed[k] for k in front[np.argsort(points[front, 0])]]
    return passed[:BEST_LISTED]


def failure_classes(rows: list[dict[str, str]]) -> list[dict]:
    """The cases that did not pass, grouped by status, exit class and what binds; most frequent first, each with
    one of its errors."""
    counts = Counter((row["status"], row["exit_class"], row["binding"]) for row in rows if row["status"] != PASSED)
    example = {(row["status"], row["exit_class"], row["binding"]): row["error"] for row in rows}
    return [{"status": status, "exit_class": int(code) if code else None, "binding": binding, "cases": count,
             "example_error": example[status, code, binding]}
            for (status, code, binding), count in counts.most_common()]


def _markdown(spec: StudySpec, rows: list[dict[str, str]], best: list[dict[str, str]], classes: list[dict],
              figures: list[str]) -> str:
    statuses = Counter(row["status"] for row in rows)
    lines = [f"# {spec.title}", "", f"`transplanter {spec.command}` on {spec.problem_file}, "
             f"{len(rows)} cases varying {', '.join(spec.fields)}: "
             + ", ".join(f"{count} {status}" for status, count in statuses.most_common()) + ".", "",
             "Every case's row is in cases.csv, its report in cases/<case_id>/report.json.", ""]
    shown = [*spec.fields, *spec.collect]
    lines += ["## Best cases" + (" (Pareto front)" if spec.objectives else ""), ""]
    if best:
        lines += ["| case_id | " + " | ".join(shown) + " |", "|" + " --- |" * (len(shown) + 1)]
        lines += [f"| {row['case_id']} | " + " | ".join(row[c] for c in shown) + " |" for row in best]
    else:
        lines += ["No case passed every check."]
    lines += ["", "## Failure classes", ""]
    if classes:
        lines += ["| status | exit class | what binds | cases | an error |", "| --- | --- | --- | --- | --- |"]
        lines += [f"| {c['status']} | {'' if c['exit_class'] is None else c['exit_class']} | {c['binding']} | "
                  f"{c['cases']} | {c['example_error'].replace('|', '/')} |" for c in classes]
    else:
        lines += ["Every case passed."]
    lines += ["", *(f"![{stem}]({stem})" for stem in figures)]
    return "\n".join(lines) + "\n"


def write_summary(spec: StudySpec, folder: Path, rows: list[dict[str, str]]):
    """Write the figures, report.md and report.json (listing every file of the folder but the cases' reports,
    which sit under cases/) into ``folder``."""
    figures = draw_figures(spec, rows)
    for stem, figure in figures.items():
        with staged_file(folder / f"{stem}.png") as partial:
            figure.savefig(partial, dpi=120)
    best, classes = best_cases(spec, rows), failure_classes(rows)
    names = [f"{stem}.png" for stem in figures]
    with staged_file(folder / "report.md") as partial:
        partial.write_text(_markdown(spec, rows, best, classes, names))
    listed = files_by_kind([*names, "report.md", "report.json", "cases.csv", STUDY_FILE])
    report = {"title": spec.title, "study": study_hash(spec), "source": spec.source, "command": spec.command,
              "problem": spec.problem_file, "fields": list(spec.fields), "collect": list(spec.collect),
              "cases": len(rows), "statuses": dict(Counter(row["status"] for row in rows)),
              "best_cases": [row["case_id"] for row in best], "failure_classes": classes,
              "case_reports": sorted(f"cases/{row['case_id']}/report.json" for row in rows), "files": listed}
    with staged_file(folder / "report.json") as partial:
        partial.write_text(report_json(report) + "\n")

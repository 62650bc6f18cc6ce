"""Onion-transplanter reports as JSON (report.json) and Markdown (report.md): a designed mechanism
(``ParallelogramResult``) and a given design evaluated (``DesignReport``)."""
from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from transplanter.gears.solid_files import solids_note
from transplanter.parallelogram.evaluation import problem_design
from transplanter.parallelogram.objectives import OBJECTIVES
from transplanter.parallelogram.problem import FILE_NAMES, PUBLISHED_FIELDS, TRANSLATION_ONLY
from transplanter.parallelogram.result import objective_values

if TYPE_CHECKING:
    from transplanter.gears.result import GearResult
    from transplanter.parallelogram.evaluation import DesignFile, Evaluation
    from transplanter.parallelogram.problem import ParallelogramProblem
    from transplanter.parallelogram.result import DesignReport, ParallelogramResult, Polished

#: The figures a paper publishes (``PUBLISHED_FIELDS``): their column in the report and the evaluation's value.
PAPER_COLUMNS: dict[str, tuple[str, Callable[[Evaluation], float]]] = {
    "depth_mm": ("depth H (mm)", lambda e: e.depth),
    "vx_release_mm_s": ("Vx at release (mm/s)", lambda e: e.vx_release),
    "vertical_range_mm": ("vertical range Y (mm)", lambda e: e.vertical_range),
    "spacing_mm": ("plant spacing (mm)", lambda e: e.spacing),
}


def variables_json(design: dict) -> dict:
    """The eight variables as in a file (mm, alpha in degrees)."""
    return {FILE_NAMES[k]: (float(np.degrees(v)) if k == "alpha" else float(v)) for k, v in design.items()
            if k in FILE_NAMES}


def objectives_json(values) -> dict:
    """f1, f2, f3 by name (``OBJECTIVES``)."""
    return dict(zip(OBJECTIVES, (float(v) for v in values), strict=True))


def evaluation_json(evaluation: Evaluation) -> dict:
    """One design under one gear reading and one set of conventions (mm, mm/s, s, deg)."""
    e = evaluation
    return {"curve": e.label, "conventions": e.conventions, "m12": e.m12,
            "center_distance": e.center_distance, "driven_turn_deg": e.driven_turn_deg,
            "depth_mm": e.depth, "vx_release_mm_s": e.vx_release, "ax_release_mm_s2": e.ax_release,
            "vertical_range_mm": e.vertical_range, "spacing_mm": e.spacing,
            "planting_time_s": e.planting_time, "depth_window_cut": e.window_cut,
            "gear_convex": e.convex, "gear_undercut_free": e.undercut_free,
            "min_curvature_radius_mm": list(e.min_curvature_radius)}


def trajectory_json(evaluation: Evaluation) -> dict:
    """``trajectory`` summary of report.json."""
    return {"depth_mm": evaluation.depth, "vx_release_mm_s": evaluation.vx_release,
            "vertical_range_mm": evaluation.vertical_range, "spacing_mm": evaluation.spacing,
            "planting_time_s": evaluation.planting_time, "ax_release_mm_s2": evaluation.ax_release}


def conventions_json(problem: ParallelogramProblem) -> dict:
    c = problem.conventions
    return {"crank_sense": "counterclockwise" if c.crank_sense > 0 else "clockwise",
            "alpha_reference_deg": float(np.degrees(c.alpha_reference)), "alpha_instant": c.alpha_instant,
            "forward": "+x" if c.forward > 0 else "-x", "forward_speed_mm_s": problem.forward_speed,
            "driver_speed_rpm": problem.driver_speed * 60 / (2 * np.pi),
            "crank_pivot_mm": [float(v) for v in problem.crank_pivot], "depth_window_mm": problem.depth_window}


def _paper(given: DesignFile) -> dict:
    return {k: given.published[k] for k in PUBLISHED_FIELDS if k in given.published}


def published_json(given: DesignFile, evaluations: list[Evaluation]) -> dict:
    """``published`` of report.json: the paper's figures, its printed gear values, every evaluation."""
    return {"paper": _paper(given), "printed": dict(given.printed),
            "evaluations": [evaluation_json(e) for e in evaluations]}


def _teeth(gear: GearResult) -> tuple[list[int] | None, list[float] | None]:
    """Nearest whole tooth counts and the fractional ones at the module (None without a module)."""
    counts = gear.tooth_counts
    return (None, None) if counts is None else (list(counts.counts), list(counts.fractional))


def gear_json(gear: GearResult) -> dict:
    """``gear`` of report.json: center distance (mm), tooth counts, convexity and undercut of both gears."""
    d = gear.design
    teeth, fractional = _teeth(gear)
    return {"center_distance": d.center_distance, "closure_error_rad": d.closure_error,
            "scale": d.driver.scale, "module": gear.problem.module, "teeth": teeth, "teeth_fractional": fractional,
            "convex": gear.convex, "undercut": gear.undercut,
            "min_curvature_radius_mm": gear.min_convex_curvature_radius,
            "ratio_range": [float(d.ratio.min()), float(d.ratio.max())], "joints": d.joints}


def polished_json(polished: Polished, problem: ParallelogramProblem) -> dict:
    out = {"status": polished.status, "iterations": polished.iterations, "solve_seconds": polished.solve_seconds,
           "dominates_start": polished.dominates_start, "variables": None, "objectives": None, "evaluation": None}
    if polished.variables is not None and polished.evaluation is not None:      # None both when IPOPT failed
        out["variables"] = variables_json(polished.variables)
        out["objectives"] = objectives_json(objective_values(problem, polished.evaluation))
        out["evaluation"] = evaluation_json(polished.evaluation)
    return out


def pareto_variables(result: ParallelogramResult, rank: int) -> dict:
    """The Pareto design ranked ``rank`` (1 = the knee) as in a file (mm, alpha in degrees)."""
    return variables_json({**result.problem.design, **result.search.variables(rank)})


def pareto_json(result: ParallelogramResult) -> list[dict]:
    """Every Pareto design ranked from the knee: variables, objectives, depth, Vx, vertical range, centre distance."""
    s = result.search
    return [{"rank": k + 1, "variables": pareto_variables(result, k + 1),
             "objectives": objectives_json(s.objectives[k]), "depth_mm": float(s.depth[k]),
             "vx_release_mm_s": float(s.vx_release[k]), "vertical_range_mm": float(s.vertical_range[k]),
             "center_distance": float(s.center_distance[k])}
            for k in range(len(s.designs))]


def design_report_json(report: DesignReport) -> dict:
    """``--design``'s report as plain JSON types: the content of report.json."""
    return {"source": report.problem.source, "design_source": report.given.source, "title": report.given.title,
            "design": variables_json(report.given.design), "conventions": conventions_json(report.problem),
            "translation_only": [FILE_NAMES[k] for k in TRANSLATION_ONLY],
            "published": published_json(report.given, report.evaluations),
            "gear": gear_json(report.gear), "trajectory": trajectory_json(report.closed),
            **({"tolerance": report.tolerance.to_json()} if report.tolerance else {}),
            "timings_s": report.timings_s}


def parallelogram_result_json(result: ParallelogramResult) -> dict:
    """The design job's report as plain JSON types: the content of report.json."""
    pareto = pareto_json(result)
    problem, e = result.problem, result.evaluation
    return {"source": problem.source, "title": problem.title,
            "conventions": conventions_json(problem),
            "translation_only": [FILE_NAMES[k] for k in TRANSLATION_ONLY],
            "searched": [FILE_NAMES[k] for k in result.search.names],
            "search": {"population": problem.population, "generations": problem.generations,
                       "seed": problem.seed, "evaluations": result.search.evaluations,
                       "depth_band_mm": list(problem.depth_band), "depth_target_mm": problem.depth_target,
                       "vertical_range_target_mm": problem.vertical_range_target},
            "pareto": pareto, "knee": pareto[0], "pick": result.pick,
            "chosen": {"variables": variables_json(result.chosen),
                       "objectives": objectives_json(objective_values(problem, e)),
                       "evaluation": evaluation_json(e)},
            "start": evaluation_json(result.start),
            "published": published_json(problem_design(problem), result.published),
            "gear": gear_json(result.gear), "solids": solids_note(result.gear, problem.solid_sizes),
            "trajectory": trajectory_json(result.final_evaluation),
            "design": variables_json(result.final),
            "polished": None if result.polished is None else polished_json(result.polished, problem),
            **({"tolerance": result.tolerance.to_json()} if result.tolerance else {}),
            "timings_s": result.timings_s}


def _fmt(value, digits: int = 4) -> str:
    if value is None:
        return "-"
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def _variables(design: dict) -> list[str]:
    rows = [f"| {name} | {_fmt(value, 6)} |" for name, value in variables_json(design).items()]
    return ["| variable | value |", "|---|---|", *rows]


def _gear(gear: GearResult) -> list[str]:
    d, radii = gear.design, gear.min_convex_curvature_radius
    teeth, fractional = _teeth(gear)
    return [f"Gear pair (gear library): center distance {d.center_distance:.4f} mm (closure error "
            f"{d.closure_error:.2g} rad), module {_fmt(gear.problem.module)} mm: "
            f"{_fmt(fractional[0] if fractional else None, 6)} teeth fit the driver "
            f"(nearest {teeth[0] if teeth else '-'}); convex {gear.convex}, undercut "
            f"{gear.undercut}, smallest curvature radii {_fmt(radii[0])} and {_fmt(radii[1])} mm.", ""]


def _solids(note: str | None) -> list[str]:
    return [] if note is None else [note + ".", ""]


def _trajectory(e: Evaluation) -> list[str]:
    return [f"Field trajectory (closed curve, the file's conventions): depth H = {e.depth:.3f} mm, Vx at "
            f"release {e.vx_release:.3f} mm/s (ax {e.ax_release:.1f} mm/s²), vertical range Y = "
            f"{e.vertical_range:.3f} mm, plant spacing {e.spacing:.2f} mm, planting instant "
            f"t_E = {e.planting_time:.4f} s.", ""]


def _published(given: DesignFile, evaluations: list[Evaluation]) -> list[str]:
    """The paper's figures against every evaluation (curve as printed / closed, conventions)."""
    lines = ["## Published figures against the evaluations", "",
             "| curve | conventions | m12 | a (mm) | phi2 per turn (deg) | "
             + " | ".join(label for label, _ in PAPER_COLUMNS.values()) + " |", "|---" * 9 + "|"]
    paper = _paper(given)
    if paper:
        lines.append("| paper | | | | | " + " | ".join(_fmt(paper.get(k)) for k in PAPER_COLUMNS) + " |")
    for e in evaluations:
        lines.append(f"| {e.label} | {e.conventions} | {e.m12:.4g} | {e.center_distance:.4f} | "
                     f"{e.driven_turn_deg:.2f} | " + " | ".join(_fmt(value(e)) for _, value in PAPER_COLUMNS.values())
                     + " |")
    return lines + [""]


def _figures(files: Sequence[str]) -> list[str]:
    return [f"![{name}]({name})" for name in files if name.endswith(".png")]


def evaluation_markdown(report: DesignReport, files: Sequence[str] = ()) -> str:
    """report.md of ``--design``."""
    given = report.given
    lines = [f"# Given design {given.source}", "", given.title, "", *_variables(given.design), "",
             "l2, l5, l6 only translate the path: no objective depends on them.", "",
             *_published(given, report.evaluations), *_trajectory(report.closed), *_gear(report.gear)]
    lines += ["", *report.tolerance.to_markdown()] if report.tolerance else []
    lines += _figures(files)
    return "\n".join(lines) + "\n"


def _objectives(values, digits: int) -> str:
    return ", ".join(f"{k} = {v:.{digits}g}" for k, v in objectives_json(values).items())


def to_markdown(result: ParallelogramResult, files: Sequence[str] = ()) -> str:
    """report.md of the design job."""
    problem, search = result.problem, result.search
    names = list(pareto_variables(result, 1))
    lines = [f"# Onion transplanter: {problem.title or problem.source}", "",
             f"NSGA-II over {', '.join(FILE_NAMES[k] for k in search.names)} (fixed: "
             f"{', '.join(FILE_NAMES[k] for k in TRANSLATION_ONLY)}, which only translate the path): population "
             f"{problem.population}, {problem.generations} generations, seed {problem.seed}, {search.evaluations} "
             f"evaluations, {len(search.designs)} Pareto designs. Depth band {list(problem.depth_band)} mm, f2 target "
             f"{problem.depth_target:g} mm, f3 target {problem.vertical_range_target:g} mm.", "",
             f"## Chosen design (rank {result.pick}; 1 = the knee)", "", *_variables(result.chosen), "",
             "Objectives (fine grid): " + _objectives(objective_values(problem, result.evaluation), 4), "",
             *_trajectory(result.final_evaluation), *_gear(result.gear),
             *_solids(solids_note(result.gear, problem.solid_sizes)),
             *_published(problem_design(problem), result.published),
             "## Pareto designs (first 10)", "",
             "| rank | " + " | ".join(names) + " | f1 | f2 | f3 |", "|---" * (len(names) + 4) + "|"]
    for k in range(min(10, len(search.designs))):
        lines.append(f"| {k + 1} | " + " | ".join(_fmt(v, 5) for v in pareto_variables(result, k + 1).values())
                     + " | " + " | ".join(_fmt(float(v), 3) for v in search.objectives[k]) + " |")
    p = result.polished
    if p is not None and p.variables and p.evaluation is not None:
        lines += ["", "## NLP polish (IPOPT, exact derivatives) of the chosen design", "", *_variables(p.variables), "",
                  f"IPOPT: {p.status}, {p.iterations} iterations, {p.solve_seconds:.3f} s. Objectives on the "
                  "fine grid: " + _objectives(objective_values(problem, p.evaluation), 3)
                  + f"; dominates the chosen design: {p.dominates_start}. The gear pair, tables and figures are "
                  "this design's.", ""]
    elif p is not None:
        lines += ["", f"NLP polish failed: IPOPT status {p.status}.", ""]
    lines += ["", *result.tolerance.to_markdown()] if result.tolerance else []
    lines += ["", "Timings (s): " + ", ".join(f"{k} {v:.2f}" for k, v in result.timings_s.items()), ""]
    lines += _figures(files)
    return "\n".join(lines) + "\n"

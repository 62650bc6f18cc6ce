"""Onion-transplanter reports (``DesignReport.to_json``, ``ParallelogramResult.to_json``) as Markdown."""
from __future__ import annotations

PAPER_LABELS = {"depth_mm": "depth H (mm)", "vx_release_mm_s": "Vx at release (mm/s)",
                "vertical_range_mm": "vertical range Y (mm)", "spacing_mm": "plant spacing (mm)"}


def _fmt(value, digits: int = 4) -> str:
    if value is None:
        return "-"
    return f"{value:.{digits}g}" if isinstance(value, float) else str(value)


def _variables(design: dict) -> list[str]:
    return ["| variable | value |", "|---|---|"] + [f"| {k} | {_fmt(v, 6)} |" for k, v in design.items()]


def _gear(gear: dict) -> list[str]:
    return [f"Gear pair (gear library): center distance {gear['center_distance']:.4f} mm (closure error "
            f"{gear['closure_error_rad']:.2g} rad), module {_fmt(gear['module'])} mm: "
            f"{_fmt(gear['teeth_fractional'][0] if gear['teeth_fractional'] else None, 6)} teeth fit the driver "
            f"(nearest {gear['teeth'][0] if gear['teeth'] else '-'}); convex {gear['convex']}, undercut "
            f"{gear['undercut']}, smallest curvature radii {_fmt(gear['min_curvature_radius_mm'][0])} and "
            f"{_fmt(gear['min_curvature_radius_mm'][1])} mm.", ""]


def _trajectory(t: dict) -> list[str]:
    return [f"Field trajectory (closed curve, the file's conventions): depth H = {t['depth_mm']:.3f} mm, Vx at "
            f"release {t['vx_release_mm_s']:.3f} mm/s (ax {t['ax_release_mm_s2']:.1f} mm/s²), vertical range Y = "
            f"{t['vertical_range_mm']:.3f} mm, plant spacing {t['spacing_mm']:.2f} mm, planting instant "
            f"t_E = {t['planting_time_s']:.4f} s.", ""]


def _published(published: dict) -> list[str]:
    """The paper's figures against every evaluation (curve as printed / closed, conventions)."""
    lines = ["## Published figures against the evaluations", "",
             "| curve | conventions | m12 | a (mm) | phi2 per turn (deg) | " + " | ".join(PAPER_LABELS.values()) + " |",
             "|---" * 9 + "|"]
    paper = published["paper"]
    if paper:
        lines.append("| paper | | | | | " + " | ".join(_fmt(paper.get(k)) for k in PAPER_LABELS) + " |")
    for e in published["evaluations"]:
        lines.append(f"| {e['curve']} | {e['conventions']} | {e['m12']:.4g} | {e['center_distance']:.4f} | "
                     f"{e['driven_turn_deg']:.2f} | " + " | ".join(_fmt(e[k]) for k in PAPER_LABELS) + " |")
    return lines + [""]


def evaluation_markdown(report: dict, figures: list[str] = ()) -> str:
    """report.md of ``--design``."""
    published = report["published"]
    lines = [f"# Given design {report['design_source']}", "", report["title"], "", *_variables(report["design"]), "",
             "l2, l5, l6 only translate the path: no objective depends on them.", "",
             *_published(published), *_trajectory(report["trajectory"]), *_gear(report["gear"])]
    lines += [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"


def to_markdown(report: dict, figures: list[str] = ()) -> str:
    """report.md of the design job."""
    search, chosen = report["search"], report["chosen"]
    lines = [f"# Onion transplanter: {report['title'] or report['source']}", "",
             f"NSGA-II over {', '.join(report['searched'])} (fixed: {', '.join(report['translation_only'])}, which only "
             f"translate the path): population {search['population']}, {search['generations']} generations, seed "
             f"{search['seed']}, {search['evaluations']} evaluations, {len(report['pareto'])} Pareto designs. Depth band "
             f"{search['depth_band_mm']} mm, f2 target {search['depth_target_mm']:g} mm, f3 target "
             f"{search['vertical_range_target_mm']:g} mm.", "",
             f"## Chosen design (rank {report['pick']}; 1 = the knee)", "", *_variables(chosen["variables"]), "",
             "Objectives (fine grid): " + ", ".join(f"{k} = {v:.4g}" for k, v in chosen["objectives"].items()), "",
             *_trajectory(report["trajectory"]), *_gear(report["gear"]),
             *_published(report["published"]),
             "## Pareto designs (first 10)", "",
             "| rank | " + " | ".join(report["pareto"][0]["variables"]) + " | f1 | f2 | f3 |",
             "|---" * (len(report["pareto"][0]["variables"]) + 4) + "|"]
    for row in report["pareto"][:10]:
        lines.append(f"| {row['rank']} | " + " | ".join(_fmt(v, 5) for v in row["variables"].values()) + " | "
                     + " | ".join(_fmt(v, 3) for v in row["objectives"].values()) + " |")
    p = report.get("polished")
    if p and p["variables"]:
        lines += ["", "## NLP polish (IPOPT, exact derivatives) of the chosen design", "", *_variables(p["variables"]), "",
                  f"IPOPT: {p['status']}, {p['iterations']} iterations, {p['solve_seconds']:.3f} s. Objectives on the "
                  "fine grid: " + ", ".join(f"{k} = {v:.3g}" for k, v in p["objectives"].items())
                  + f"; dominates the chosen design: {p['dominates_start']}. The gear pair, tables and figures are "
                  "this design's.", ""]
    elif p:
        lines += ["", f"NLP polish failed: IPOPT status {p['status']}.", ""]
    lines += ["", "Timings (s): " + ", ".join(f"{k} {v:.2f}" for k, v in report["timings_s"].items()), ""]
    lines += [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"

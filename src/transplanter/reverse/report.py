"""A reverse-design report (``ReverseResult.to_json``) as Markdown."""
from __future__ import annotations


def to_markdown(report: dict, figures: list[str]) -> str:
    lines = [f"# Reverse design: {report['title'] or report['source']}", "",
             f"- Path: {report['trajectory']['points']} {report['trajectory']['kind'].replace('_', ' ')}, farthest "
             f"{report['trajectory']['farthest_mm']:.4f} mm and nearest {report['trajectory']['nearest_mm']:.4f} mm "
             f"from the pivot {report['trajectory']['pivot']}"
             + (f"; the curve fitted to the samples misses them by up to {report['trajectory']['fit_residual_mm']:.3g} mm"
                if report["trajectory"]["fit_residual_mm"] is not None else ""),
             f"- Carrier s = {report['carrier_length']:.4f} mm, arm l = {report['arm_length']:.4f} mm "
             f"({report['lengths_from']}), carrier turning {report['direction']}",
             "- Branches: " + ", ".join(f"{s['branch']} on u {s['u'][0]:.4f}-{s['u'][1]:.4f}"
                                        for s in report["branch_segments"])
             + (f"; switches at u = {', '.join(f'{u:.4f}' for u in report['branch_switches_u'])} (the path touches "
                "the reach circles there)" if report["branch_switches_u"] else ""),
             f"- Monotonicity criterion (the reverse-gear-design paper): {'met' if report['monotonic'] else 'NOT met'}"]
    for violation in report["violations"]:
        lines.append(f"  - {violation['condition']}: {violation['message']}")
    for hint in report["fix_hints"]:
        lines.append(f"  - would pass with: {hint}")
    if report["monotonic"]:
        lines += [f"- Train: {report['topology']}, split {report['split']}; total ratio i0 from "
                  f"{report['ratio_range'][0]:.4f} to {report['ratio_range'][1]:.4f}",
                  f"- Gear closure errors (rad): {', '.join(f'{e:.2e}' for e in report['gear_closure_errors'])}",
                  f"- Round trip (gears rolled from their pitch curves, tip rebuilt): largest miss "
                  f"{report['roundtrip_max_error_mm']:.3e} mm", "",
                  "| gear | radius min (mm) | radius max (mm) | convex | perimeter (mm) | teeth at the module |",
                  "| --- | --- | --- | --- | --- | --- |"]
        lines += [f"| {g['gear']} | {g['radius_range_mm'][0]:.3f} | {g['radius_range_mm'][1]:.3f} | {g['convex']} | "
                  f"{g['perimeter_mm']:.3f} | {g['teeth_at_module']:.2f} |" for g in report["gears"]]
        if "idler_iteration" in report:
            it = report["idler_iteration"]
            lines += ["", f"The rice-transplanter paper's iteration: {it['iterations']} iterations, "
                      f"settled: {it['settled']}, eq (5) model "
                      f"residual {it['eq5_model_residual']:.3e}; the train as built misses the path by "
                      f"{report['roundtrip_max_error_mm']:.3f} mm (see docs/reverse.md, 'Published findings')."]
        if "printed_peak_to_valley_intermediate_turn_deg" in report:
            lines += ["", "The reverse-gear-design paper's split as printed (i1 = i25 bs) would turn the intermediate gear "
                      f"{report['printed_peak_to_valley_intermediate_turn_deg']:.3f} deg per cycle (360 closes)."]
    lines += [""] + [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"

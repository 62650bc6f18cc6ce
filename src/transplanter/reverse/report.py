"""JSON and Markdown reports of a reverse design."""
from __future__ import annotations

import numpy as np

from transplanter.reverse.arm_inverse import BRANCH_NAMES, DIRECTION_NAMES
from transplanter.geometry.closed_trajectory import TWO_PI
from transplanter.reverse.idler_train import IdlerTrain
from transplanter.trains.planetary import printed_peak_to_valley_turn
from transplanter.reverse.synthesis import ReverseResult


def _gear(name: str, radius: np.ndarray, convexity: np.ndarray, perimeter: float, module: float) -> dict:
    return {"gear": name, "radius_range_mm": [float(radius.min()), float(radius.max())],
            "convex": bool(np.all(convexity > 0)), "perimeter_mm": perimeter,
            "teeth_at_module": perimeter / (np.pi * module)}


def _gears(result: ReverseResult) -> tuple[list[dict], list[float]]:
    train, module = result.train, result.problem.module
    one, two = train.stage_one, train.stage_two
    gears = [_gear("sun", one.radius[0], one.convexity[0], one.perimeters[0], module)]
    if isinstance(train, IdlerTrain):
        gears += [_gear("idler", one.radius[1], one.convexity[1], one.perimeters[1], module),
                  _gear("planet", two.radius[1], two.convexity[1], two.perimeters[1], module)]
        return gears, [one.closure_error, two.closure_error]
    gears += [_gear("first intermediate", one.radius[1], one.convexity[1], one.perimeters[1], module),
              _gear("second intermediate", two.radius[0], two.convexity[0], two.perimeters[0], module),
              _gear("planet", two.radius[1], two.convexity[1], two.perimeters[1], module)]
    return gears, [one.closure_error, two.closure_error]


def branch_segments(result: ReverseResult) -> list[dict]:
    motion = result.motion
    cuts = [0.0] + [t.parameter for t in motion.touches] + [TWO_PI]
    return [{"u": [a / TWO_PI, b / TWO_PI], "branch": BRANCH_NAMES[int(motion.branch(np.array((a + b) / 2)))]}
            for a, b in zip(cuts[:-1], cuts[1:]) if b > a]


def to_json(result: ReverseResult) -> dict:
    problem, motion = result.problem, result.motion
    report = {
        "title": problem.title, "source": problem.source,
        "trajectory": {"kind": problem.kind, "points": len(problem.points), "pivot": problem.pivot.tolist(),
                       "farthest_mm": result.extremes[0], "nearest_mm": result.extremes[1]},
        "carrier_length": motion.carrier_length, "arm_length": motion.arm_length,
        "lengths_from": "path extremes (seed 002 eq 1-2)" if result.lengths_derived else "problem file",
        "direction": DIRECTION_NAMES[motion.direction],
        "touches": [{"u": t.parameter / TWO_PI, "circle": t.circle, "gap_mm": t.gap_mm} for t in motion.touches],
        "branch_segments": branch_segments(result),
        "branch_switches_u": [t.parameter / TWO_PI for t in motion.touches],
        "monotonic": result.monotonic,
        "violations": [v.to_json() for v in result.violations],
        "fix_hints": result.hints,
        "topology": problem.topology, "split": problem.split,
    }
    if not result.monotonic:
        return report
    ratio = result.motion.total_ratio()
    gears, closure = _gears(result)
    report.update({
        "ratio_range": [float(ratio.min()), float(ratio.max())],
        "gears": gears, "gear_closure_errors": closure,
        "roundtrip_max_error_mm": result.verification.max_error_mm,
        "contact_gap_max_mm": max(float(np.abs(g).max()) for g in result.verification.contact_gaps_mm),
    })
    train = result.train
    if isinstance(train, IdlerTrain):
        report["idler_iteration"] = {"iterations": train.iterations, "settled": bool(train.converged),
                                     "eq5_model_residual": train.model_residual, "correction_x": train.correction,
                                     "center_distance_mm": train.center_distance}
    else:
        report.update({"center_distances": list(train.center_distances), "correction_factor_k": train.correction,
                       "stage_one_exponent": train.exponent})
        if result.geometry is not None:
            report["carrier_bend_deg"] = float(np.degrees(result.geometry.bend))
        if problem.split == "peak_to_valley":
            report["printed_peak_to_valley_intermediate_turn_deg"] = float(
                np.degrees(printed_peak_to_valley_turn(result.relative, problem.peak_to_valley)))
    return report


def to_markdown(report: dict, figures: list[str]) -> str:
    lines = [f"# Reverse design: {report['title'] or report['source']}", "",
             f"- Path: {report['trajectory']['points']} {report['trajectory']['kind'].replace('_', ' ')}, farthest "
             f"{report['trajectory']['farthest_mm']:.4f} mm and nearest {report['trajectory']['nearest_mm']:.4f} mm "
             f"from the pivot {report['trajectory']['pivot']}",
             f"- Carrier s = {report['carrier_length']:.4f} mm, arm l = {report['arm_length']:.4f} mm "
             f"({report['lengths_from']}), carrier turning {report['direction']}",
             "- Branches: " + ", ".join(f"{s['branch']} on u {s['u'][0]:.4f}-{s['u'][1]:.4f}"
                                        for s in report["branch_segments"])
             + (f"; switches at u = {', '.join(f'{u:.4f}' for u in report['branch_switches_u'])} (the path touches "
                "the reach circles there)" if report["branch_switches_u"] else ""),
             f"- Monotonicity criterion (seed 003): {'met' if report['monotonic'] else 'NOT met'}"]
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
            lines += ["", f"Seed 002 iteration: {it['iterations']} iterations, settled: {it['settled']}, eq (5) model "
                      f"residual {it['eq5_model_residual']:.3e}; the train as built misses the path by "
                      f"{report['roundtrip_max_error_mm']:.3f} mm (see README, 'Published methods')."]
        if "printed_peak_to_valley_intermediate_turn_deg" in report:
            lines += ["", "Seed 003's split as printed (i1 = i25 bs) would turn the intermediate gear "
                      f"{report['printed_peak_to_valley_intermediate_turn_deg']:.3f} deg per cycle (360 closes)."]
    lines += [""] + [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"

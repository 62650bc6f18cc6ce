"""A gear-pair result as JSON and Markdown."""
from __future__ import annotations

import numpy as np

from transplanter.gears.synthesis import GearResult
from transplanter.gears.rack_teeth import ADDENDUM


def _min_convex(rho, convexity):
    convex = convexity > 0
    return float(rho[convex].min()) if convex.any() else None


def to_json(result: GearResult) -> dict:
    d, problem = result.design, result.problem
    out = {
        "source": problem.source, "title": problem.title,
        "driver": {"family": d.driver.family, "parameters": problem.parameters, "scale": d.driver.scale},
        "center_distance": d.center_distance,
        "orders": list(d.orders),
        "closure_error": d.closure_error,
        "rolling_mismatch_mm": d.rolling_mismatch_mm,
        "ratio_range": [float(d.ratio.min()), float(d.ratio.max())],
        "perimeters": list(d.perimeters),
        "convex": [bool((c > 0).all()) for c in d.convexity],
        "min_curvature_radius": [_min_convex(r, c) for r, c in zip(d.curvature_radius, d.convexity)],
        "joints": d.joints,
        "driver_speed_rad_s": d.driver_speed,
        "driven_speed_range_rad_s": [float(d.driven_speed.min()), float(d.driven_speed.max())],
        "driven_acceleration_range_rad_s2": [float(d.driven_acceleration.min()), float(d.driven_acceleration.max())],
        "ratio_correction_factor": result.ratio_correction,
        "module": problem.module,
        "tooth_counts": None, "undercut": None, "contact_ratio_range": None, "self_intersections": None,
        "timings_s": result.timings_s,
    }
    if result.tooth_counts is not None:
        counts = result.tooth_counts
        limit = ADDENDUM * counts.module / np.sin(problem.pressure_angle) ** 2
        out["tooth_counts"] = {"fractional": list(counts.fractional), "nearest": list(counts.counts),
                               "exact_module": counts.exact_module, "scale_for_module": counts.scale_for_module}
        out["undercut"] = [bool(v is not None and v < limit) for v in out["min_curvature_radius"]]
    if result.teeth is not None:
        out["cutter"] = result.teeth.cutter
        out["contact_ratio_range"] = None if result.teeth.contact_ratio is None else list(result.teeth.contact_ratio)
        out["self_intersections"] = list(result.teeth.self_intersections)
    return out


def to_markdown(report: dict, figures: list[str], drawings: list[str]) -> str:
    lines = [f"# {report['title'] or report['source']}", "",
             f"- driver: {report['driver']['family']} {report['driver']['parameters']} (scaled by {report['driver']['scale']:.9g})",
             f"- orders n1, n2: {report['orders']}; center distance {report['center_distance']:.9f} mm; "
             f"closure error {report['closure_error']:.1e} rad; rolling mismatch {report['rolling_mismatch_mm']:.1e} mm",
             f"- ratio i12 = omega1/omega2 from {report['ratio_range'][0]:.6f} to {report['ratio_range'][1]:.6f}"
             + ("" if report["ratio_correction_factor"] is None else
                f" (the given ratio times k = {report['ratio_correction_factor']:.9f}, seed 000 eq 12)"),
             f"- perimeters {report['perimeters'][0]:.6f} and {report['perimeters'][1]:.6f} mm; convex {report['convex']}; "
             f"smallest convex curvature radius {report['min_curvature_radius']} mm"]
    for joint in report["joints"]:
        lines.append(f"- joint at {joint['phi_deg']:.4f} deg: jumps of r {joint['radius_jump']:.2e} mm, "
                     f"r' {joint['slope_jump']:.2e} mm/rad, r'' {joint['bend_jump']:.4g} mm/rad^2")
    if report["tooth_counts"]:
        counts = report["tooth_counts"]
        lines.append(f"- module {report['module']:g}: {counts['fractional'][0]:.4f} and {counts['fractional'][1]:.4f} "
                     f"teeth; nearest {counts['nearest']}, exact with module {counts['exact_module']:.6f} or with the "
                     f"curves scaled by {counts['scale_for_module']:.6f}; undercut {report['undercut']}")
    if report["self_intersections"] is not None:
        contact = report["contact_ratio_range"]
        lines.append(f"- tooth profiles by {report['cutter']} envelope; self-intersections {report['self_intersections']}"
                     + ("" if contact is None else f"; local contact ratio {contact[0]:.3f} to {contact[1]:.3f} "
                        "(osculating spur pair, convex parts)"))
    if drawings:
        lines += ["", "Drawings: " + ", ".join(drawings)]
    lines += [""] + [f"![{f}]({f})" for f in figures]
    return "\n".join(lines) + "\n"

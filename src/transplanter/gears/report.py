"""A gear pair as JSON (report.json) and Markdown (report.md): the pair, its teeth and, for a pitch
curve with corners, the composite teeth and their checks."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import asdict
from typing import TYPE_CHECKING

import numpy as np

from transplanter.gears.composite_curve import CompositeCurve, cusps
from transplanter.gears.composite_teeth import CompositeTeeth, CornerPressureTrial
from transplanter.gears.solid_files import solids_note

if TYPE_CHECKING:
    from transplanter.gears.mesh_check import MeshCheck
    from transplanter.gears.result import GearResult


def mesh_check_json(check: MeshCheck) -> dict:
    """A mesh check over a turn (mm, degrees): overlap, clearance, contact gap, transmission error, verdict."""
    return {"max_overlap_mm": check.max_overlap_mm, "min_clearance_mm": check.min_clearance_mm,
            "max_contact_gap_mm": check.max_contact_gap_mm,
            "transmission_error_deg": float(np.degrees(check.max_transmission_error_rad)),
            "transmission_error_mm": check.max_transmission_error_mm, "positions": len(check.driver_angle),
            "passed": check.passed, "failures": check.failures}


def _trial_json(trial: CornerPressureTrial) -> dict:
    if trial.refused is not None:
        return {"corner_pressure_angle_deg": trial.degrees, "refused": trial.refused}
    return {"corner_pressure_angle_deg": trial.degrees, "passed": trial.passed, "failures": list(trial.failures),
            "transmission_error_mm": trial.transmission_error_mm}


def composite_teeth_json(teeth: CompositeTeeth) -> dict:
    """The composite teeth's part of report.json (mm, degrees)."""
    contact = teeth.contact
    return {
        "tooth_counts_built": list(teeth.counts),
        "contact_ratio_min": contact.minimum,
        "contact_ratio_where": contact.where()._asdict(),
        "contact_lost_at_deg": {"low-arc": contact.uncovered_deg[0].tolist(),
                                "high-arc": contact.uncovered_deg[1].tolist()},
        "variable_involute": asdict(teeth.involute),
        "corner_pressure_angle_deg": teeth.corner_pressure_deg,
        "corner_pressure_trials": [_trial_json(trial) for trial in teeth.trials],
        "mesh_check": mesh_check_json(teeth.mesh),
        "corner_teeth": [{"corner_arc_mm": t.corner_arc, "thickness_pitches": t.thickness_ratio,
                          "rolling_radii_mm": [a.radius for a in t.arches],
                          "joint_heights_mm": [a.joint_height for a in t.arches],
                          "corner_heights_mm": [a.corner_height for a in t.arches],
                          "joint_kinks_deg": list(t.joint_kinks_deg), "joint_gaps_mm": list(t.joint_gaps_mm),
                          "arch_pressure_angles_deg": [list(p) for p in t.pressure_angles_deg],
                          "arch_min_curvature_radius_mm": list(t.min_curvature_radius_mm)}
                         for t in teeth.corner_teeth],
    }


def _cusps(result: GearResult) -> list[dict] | None:
    """The driver's corners (``composite_curve.cusps``) at the pair's center distance; None for a smooth driver."""
    d = result.design
    return cusps(d.driver, d.center_distance) if isinstance(d.driver, CompositeCurve) else None


def gear_result_json(result: GearResult) -> dict:
    """The report as plain JSON types (mm, rad, rad/s): the content of report.json."""
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
        "convex": result.convex,
        "min_curvature_radius": result.min_convex_curvature_radius,
        "joints": d.joints,
        "cusps": _cusps(result),
        "driver_speed_rad_s": d.driver_speed,
        "driven_speed_range_rad_s": [float(d.driven_speed.min()), float(d.driven_speed.max())],
        "driven_acceleration_range_rad_s2": [float(d.driven_acceleration.min()), float(d.driven_acceleration.max())],
        "ratio_correction_factor": result.ratio_correction,
        "module": problem.module,
        "tooth_counts": None, "undercut": result.undercut, "contact_ratio_range": None, "self_intersections": None,
        "timings_s": result.timings_s,
        "solids": solids_note(result, problem.solid_sizes),
    }
    if result.tooth_counts is not None:
        counts = result.tooth_counts
        out["tooth_counts"] = {"fractional": list(counts.fractional), "nearest": list(counts.counts),
                               "exact_module": counts.exact_module, "scale_for_module": counts.scale_for_module}
    if result.teeth is not None:
        out["cutter"] = result.teeth.cutter
        out["contact_ratio_range"] = None if result.teeth.contact_ratio is None else list(result.teeth.contact_ratio)
        out["self_intersections"] = list(result.teeth.self_intersections)
    if isinstance(result.teeth, CompositeTeeth):
        out.update(composite_teeth_json(result.teeth))
    return out


def to_markdown(result: GearResult, files: Sequence[str] = ()) -> str:
    """report.md: the pair, its teeth, the drawings and the figures among ``files``."""
    d, problem = result.design, result.problem
    ratio, k = (float(d.ratio.min()), float(d.ratio.max())), result.ratio_correction
    lines = [f"# {problem.title or problem.source}", "",
             f"- driver: {d.driver.family} {problem.parameters} (scaled by {d.driver.scale:.9g})",
             f"- orders n1, n2: {list(d.orders)}; center distance {d.center_distance:.9f} mm; "
             f"closure error {d.closure_error:.1e} rad; rolling mismatch {d.rolling_mismatch_mm:.1e} mm",
             f"- ratio i12 = omega1/omega2 from {ratio[0]:.6f} to {ratio[1]:.6f}"
             + ("" if k is None else f" (the given ratio times k = {k:.9f}, Wang et al. 2025 eq 12)"),
             f"- perimeters {d.perimeters[0]:.6f} and {d.perimeters[1]:.6f} mm; convex {result.convex}; "
             f"smallest convex curvature radius {result.min_convex_curvature_radius} mm"]
    for joint in d.joints:
        lines.append(f"- joint at {joint['phi_deg']:.4f} deg: jumps of r {joint['radius_jump']:.2e} mm, "
                     f"r' {joint['slope_jump']:.2e} mm/rad, r'' {joint['bend_jump']:.4g} mm/rad^2")
    for cusp in _cusps(result) or []:
        lines.append(f"- cusp at {cusp['phi_deg']:.4f} deg: the driver's tangent turns {cusp['turn_deg']:.4f} deg "
                     f"(+ convex), the driven curve's {cusp['driven_turn_deg']:.4f} deg at the same contact")
    teeth = result.teeth
    if result.tooth_counts is not None:
        counts = result.tooth_counts
        lines.append(f"- module {problem.module:g}: {counts.fractional[0]:.4f} and {counts.fractional[1]:.4f} "
                     f"teeth; nearest {list(counts.counts)}, exact with module {counts.exact_module:.6f} or with the "
                     f"curves scaled by {counts.scale_for_module:.6f}; a rack would undercut {result.undercut}"
                     + ("" if teeth is None or teeth.cutter == "rack" else
                        f" (a reference only: {teeth.cutter} teeth, not rack-cut; the mesh check judges them)"))
    if teeth is not None:
        contact = teeth.contact_ratio
        lines.append(f"- tooth profiles by {teeth.cutter} envelope; self-intersections {list(teeth.self_intersections)}"
                     + ("" if contact is None else f"; local contact ratio {contact[0]:.3f} to {contact[1]:.3f} "
                        "(osculating spur pair, convex parts)"))
    if isinstance(teeth, CompositeTeeth):
        lines += _composite_lines(teeth)
    note = solids_note(result, problem.solid_sizes)
    lines += [] if note is None else [f"- {note}"]
    drawings = [name for name in files if not name.endswith(".png")]
    if drawings:
        lines += ["", "Drawings: " + ", ".join(drawings)]
    lines += [""] + [f"![{f}]({f})" for f in files if f.endswith(".png")]
    return "\n".join(lines) + "\n"


def _trial_line(trial: CornerPressureTrial) -> str:
    if trial.refused is not None:
        return f"{trial.degrees:g} deg refused ({trial.refused.split(': ', 1)[-1]})"
    checks = len(trial.failures)
    return (f"{trial.degrees:g} deg {'passed' if trial.passed else 'failed'} (transmission error "
            f"{trial.transmission_error_mm:.4f} mm" + ("" if trial.passed else f", {checks} check{'s' * (checks > 1)} "
                                                       "failed") + ")")


def _composite_lines(teeth: CompositeTeeth) -> list[str]:
    """The composite pair's checks and corner teeth."""
    mesh, contact, involute = teeth.mesh, teeth.contact, teeth.involute
    where = contact.where()
    lost = [f"{flank} at {', '.join(f'{a:.2f}' for a in angles)} deg"
            for flank, angles in zip(("low-arc", "high-arc"), contact.uncovered_deg, strict=True) if angles.size]
    tried = "; ".join(_trial_line(trial) for trial in teeth.trials)
    lines = [f"- corner pressure angle {teeth.corner_pressure_deg:g} deg"
             + (f" (tried: {tried})" if tried else " (given)"),
             f"- contact ratio at least {contact.minimum:.3f} (tooth {where.tooth}, {where.phi_deg:.2f} deg, "
             f"{where.flank} flank); positions without contact: " + ("; ".join(lost) if lost else "none"),
             f"- mesh through a whole turn: largest overlap {mesh.max_overlap_mm:.4f} mm, transmission error "
             f"{mesh.max_transmission_error_mm:.4f} mm ({np.degrees(mesh.max_transmission_error_rad):.4f} deg), "
             + ("passed" if mesh.passed else "FAILED"),
             f"- shaper-cut flanks within {involute.largest_mm:.4f} mm of the closed-form variable involute "
             f"({involute.flanks_compared} flanks, {involute.points_compared} points)"]
    for tooth in teeth.corner_teeth:
        pressure = [angle for pair in tooth.pressure_angles_deg for angle in pair]
        lines.append(f"- corner tooth at pitch arc {tooth.corner_arc:.3f} mm: {tooth.thickness_ratio:.3f} "
                     f"pitch thick, rolling radii {_pair([a.radius for a in tooth.arches])} mm, joints "
                     f"{_pair([a.joint_height for a in tooth.arches])} mm above the pitch curve, arch pressure angles "
                     f"{min(pressure):.1f}-{max(pressure):.1f} deg, kinks {_pair(tooth.joint_kinks_deg)} deg, "
                     f"smallest arch curvature radius {min(tooth.min_curvature_radius_mm):.3f} mm")
    return lines


def _pair(values: Sequence[float]) -> str:
    return " and ".join(f"{v:.3f}" for v in values)

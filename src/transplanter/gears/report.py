"""A gear-pair report (``GearResult.to_json``) as Markdown."""
from __future__ import annotations


def to_markdown(report: dict, figures: list[str], drawings: list[str]) -> str:
    lines = [f"# {report['title'] or report['source']}", "",
             f"- driver: {report['driver']['family']} {report['driver']['parameters']} (scaled by {report['driver']['scale']:.9g})",
             f"- orders n1, n2: {report['orders']}; center distance {report['center_distance']:.9f} mm; "
             f"closure error {report['closure_error']:.1e} rad; rolling mismatch {report['rolling_mismatch_mm']:.1e} mm",
             f"- ratio i12 = omega1/omega2 from {report['ratio_range'][0]:.6f} to {report['ratio_range'][1]:.6f}"
             + ("" if report["ratio_correction_factor"] is None else
                f" (the given ratio times k = {report['ratio_correction_factor']:.9f}, Wang et al. 2025 eq 12)"),
             f"- perimeters {report['perimeters'][0]:.6f} and {report['perimeters'][1]:.6f} mm; convex {report['convex']}; "
             f"smallest convex curvature radius {report['min_curvature_radius']} mm"]
    for joint in report["joints"]:
        lines.append(f"- joint at {joint['phi_deg']:.4f} deg: jumps of r {joint['radius_jump']:.2e} mm, "
                     f"r' {joint['slope_jump']:.2e} mm/rad, r'' {joint['bend_jump']:.4g} mm/rad^2")
    for cusp in report.get("cusps") or []:
        lines.append(f"- cusp at {cusp['phi_deg']:.4f} deg: the driver's tangent turns {cusp['turn_deg']:.4f} deg "
                     f"(+ convex), the driven curve's {cusp['driven_turn_deg']:.4f} deg at the same contact")
    if report["tooth_counts"]:
        counts = report["tooth_counts"]
        lines.append(f"- module {report['module']:g}: {counts['fractional'][0]:.4f} and {counts['fractional'][1]:.4f} "
                     f"teeth; nearest {counts['nearest']}, exact with module {counts['exact_module']:.6f} or with the "
                     f"curves scaled by {counts['scale_for_module']:.6f}; a rack would undercut {report['undercut']}"
                     + ("" if report.get("cutter", "rack") == "rack" else
                        f" (a reference only: {report['cutter']} teeth, not rack-cut; the mesh check judges them)"))
    if report["self_intersections"] is not None:
        contact = report["contact_ratio_range"]
        lines.append(f"- tooth profiles by {report['cutter']} envelope; self-intersections {report['self_intersections']}"
                     + ("" if contact is None else f"; local contact ratio {contact[0]:.3f} to {contact[1]:.3f} "
                        "(osculating spur pair, convex parts)"))
    if "corner_teeth" in report:
        lines += _composite_lines(report)
    if drawings:
        lines += ["", "Drawings: " + ", ".join(drawings)]
    lines += [""] + [f"![{f}]({f})" for f in figures]
    return "\n".join(lines) + "\n"


def _composite_lines(report: dict) -> list[str]:
    """The composite pair's checks and corner teeth (``composite_teeth_json``)."""
    mesh, where, involute = report["mesh_check"], report["contact_ratio_where"], report["variable_involute"]
    lost = [f"{flank} at {', '.join(f'{a:.2f}' for a in angles)} deg"
            for flank, angles in report["contact_lost_at_deg"].items() if angles]
    tried = "; ".join(f"{t['corner_pressure_angle_deg']:g} deg " + (
        f"refused ({t['refused'].split(': ', 1)[-1]})" if "refused" in t else
        f"{'passed' if t['passed'] else 'failed'} (transmission error {t['transmission_error_mm']:.4f} mm"
        + ("" if t["passed"] else f", {len(t['failures'])} check{'s' * (len(t['failures']) > 1)} failed") + ")")
        for t in report["corner_pressure_trials"])
    lines = [f"- corner pressure angle {report['corner_pressure_angle_deg']:g} deg"
             + (f" (tried: {tried})" if tried else " (given)"),
             f"- contact ratio at least {report['contact_ratio_min']:.3f} (tooth {where['tooth']}, "
             f"{where['phi_deg']:.2f} deg, {where['flank']} flank); positions without contact: "
             + ("; ".join(lost) if lost else "none"),
             f"- mesh through a whole turn: largest overlap {mesh['max_overlap_mm']:.4f} mm, transmission error "
             f"{mesh['transmission_error_mm']:.4f} mm ({mesh['transmission_error_deg']:.4f} deg), "
             + ("passed" if mesh["passed"] else "FAILED"),
             f"- shaper-cut flanks within {involute['largest_mm']:.4f} mm of the closed-form variable involute "
             f"({involute['flanks_compared']} flanks, {involute['points_compared']} points)"]
    for tooth in report["corner_teeth"]:
        pressure = [angle for pair in tooth["arch_pressure_angles_deg"] for angle in pair]
        lines.append(f"- corner tooth at pitch arc {tooth['corner_arc_mm']:.3f} mm: {tooth['thickness_pitches']:.3f} "
                     f"pitch thick, rolling radii {_pair(tooth['rolling_radii_mm'])} mm, joints "
                     f"{_pair(tooth['joint_heights_mm'])} mm above the pitch curve, arch pressure angles "
                     f"{min(pressure):.1f}-{max(pressure):.1f} deg, kinks {_pair(tooth['joint_kinks_deg'])} deg, "
                     f"smallest arch curvature radius {min(tooth['arch_min_curvature_radius_mm']):.3f} mm")
    return lines


def _pair(values: list[float]) -> str:
    return " and ".join(f"{v:.3f}" for v in values)

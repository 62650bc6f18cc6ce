"""Five-bar reports (``FiveBarResult.to_json``, ``DesignEvaluation.to_json``) as Markdown
(report file, terminal)."""
from __future__ import annotations


def _row(label, values, digits=3):
    return f"| {label} | " + " | ".join(f"{v:.{digits}g}" if isinstance(v, float) else str(v) for v in values) + " |"


def to_markdown(report: dict, labels: tuple[str, ...], figures: list[str]) -> str:
    d = report["design"]
    lines = [f"# Five-bar seedling pushing mechanism: {report['title'] or report['source']}", "",
             "## Key poses (forward simulation: gears rolling, then the linkage)", "",
             "| | " + " | ".join(labels) + " |", "|---" * (len(labels) + 1) + "|",
             _row("P position error (mm)", report["key_pose_position_errors_mm"]),
             _row("plate angle error (deg)", report["key_pose_angle_errors_deg"]), "",
             f"Return points reached within {max(report['return_point_errors_mm']):.3g} mm "
             f"(tolerance {report['return_tolerance_mm']:g} mm). "
             f"Gear trajectory against the designed one: {report['roundtrip_max_error_mm']:.3g} mm at most; "
             f"pitch-curve contact gap {report['contact_gap_mm']:.3g} mm.", "",
             "## Design (pose 1)", "", "| quantity | value |", "|---|---|"]
    lines += [f"| {key} | {value if isinstance(value, (str, list)) else round(value, 4)} |" for key, value in d.items()]
    lines += ["", "## Whole turn", "",
              f"- smallest transmission angle at E (between EF and BE): {report['transmission_angle_min_deg']:.2f} "
              f"deg at carrier turn {report['transmission_angle_min_at_deg']:.1f} deg; smallest closure angle EBF: "
              f"{report['closure_angle_min_deg']:.2f} deg",
              f"- smallest closure margin sin²(EBF): {report['min_closure_margin']:.5f} "
              f"(required {report['required_closure_margin']}); eq (10) discriminant ≥ {report['min_discriminant']:.4g} mm⁴",
              "- active bounds: " + (", ".join(_bound(b) for b in report["active_bounds"]) or "none"),
              f"- relative angle strictly increasing: {report['relative_angle_monotonic']}; total ratio i0 in "
              f"[{report['ratio_range'][0]:.4f}, {report['ratio_range'][1]:.4f}]", ""]
    train, mesh = report["gear_train"], report["mesh_check"]
    a1, a2 = train["center_distances_mm"]
    lines += ["## Gears (eq 11-13)", "",
              f"Correction factor k = {train['correction_k']:.6f}. Eq (12) as printed (integrating over the relative "
              f"angle) gives k = {train['printed_eq12_k']:.6f}, with which the first intermediate gear turns "
              f"{train['printed_eq12_intermediate_turn_deg']:.3f} deg per sun turn instead of 360.", "",
              f"Module {train['module']:g} mm, pressure angle {train['pressure_angle_deg']:g} deg, {train['layout']} "
              f"carrier: a1 = {a1:.4f} mm, a2 = {a2:.4f} mm, the intermediate shaft at "
              f"({train['shaft_mm'][0]:.3f}, {train['shaft_mm'][1]:.3f}) mm, bent {train['bend_angle_deg']:.2f} deg "
              "from O-A.", "",
              *([f"Pitch curves in the design NLP: {report['nlp']['convexity_note']}.", ""]
                if report["nlp"]["convexity_note"] else []),
              "| gear | role | teeth | convex | smallest convex curvature radius (mm) | cutter | why |",
              "|---|---|---|---|---|---|---|"]
    lines += [f"| {g['name']} | {g['role']} | {g['teeth']} | {g['convex']} | {g['min_curvature_radius_mm']:.3f} | "
              f"{g['cutter']} | {g['reason']} |" for g in report["gears"]]
    lines += ["", f"Tooth mesh over a turn (teeth turned by the designed motion): largest overlap "
              f"{mesh['max_overlap_mm']:.4f} mm, smallest clearance {mesh['min_clearance_mm']:.4f} mm, transmission "
              f"error {mesh['transmission_error_deg']:.4f} deg: {'passed' if mesh['passed'] else 'FAILED'}.", ""]
    lines += _alternatives(report)
    region = report["region"]
    lines += ["", "## Solution region", "",
              f"{region['receiving_kept']} of {region['receiving_dyads']} B-E dyads and {region['carrier_kept']} of "
              f"{region['carrier_dyads']} A-F dyads within ranges; {region['feasible_pairs']} of {region['pairs']} "
              f"five-bars feasible (removed by: {region['removed_by']}).", "",
              f"NLP: {report['nlp']['status']} in {report['nlp']['iterations']} iterations.", ""]
    lines += support_markdown(report)
    lines += [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"


def _bound(bound: dict) -> str:
    return f"{bound['bound']} {'>=' if bound['side'] == 'lower' else '<='} {bound['limit']:g}"


def _gear_sizes(gears: dict) -> str:
    if "none" in gears:
        return f"none: {gears['none']}"
    counts, (a1, a2), radii = gears["teeth"], gears["center_distances_mm"], gears["largest_pitch_radius_mm"]
    return (f"{counts[0]} / {counts[1]} at m {gears['module']:g} ({'/'.join(gears['cutters'])}), "
            f"{a1:.1f} / {a2:.1f}, {max(radii):.1f}")


def _alternatives(report: dict) -> list[str]:
    """The table of the ranked alternatives and the list of the candidates that failed."""
    lines = ["", "## Alternatives", "",
             f"{report['ranking_rule']} Alternative {report['picked']} is built (`--pick N` builds another).", "",
             "| # | OA | AF | EF | BE | EP | FP | B (mm) | min at E (deg) at turn | min EBF (deg) | i0 range | "
             "largest return miss (mm) | gears: teeth, a1 / a2, largest pitch radius (mm) | active bounds | "
             "from candidates |", "|---" * 15 + "|"]
    for alternative in report["alternatives"]:
        d = alternative["design"]
        mark = " (built)" if alternative["rank"] == report["picked"] else ""
        lines.append(
            f"| {alternative['rank']}{mark} | {d['carrier_length_OA']:.2f} | {d['rod_length_AF']:.2f} | "
            f"{d['plate_link_length_EF']:.2f} | {d['receiving_plate_length_BE']:.2f} | {d['push_plate_EP']:.2f} | "
            f"{d['push_plate_FP']:.2f} | ({d['hinge_B'][0]:.1f}, {d['hinge_B'][1]:.1f}) | "
            f"{alternative['transmission_angle_min_deg']:.2f} at {alternative['transmission_angle_min_at_deg']:.1f} | "
            f"{alternative['closure_angle_min_deg']:.2f} | {alternative['ratio_range'][0]:.3f}-"
            f"{alternative['ratio_range'][1]:.3f} | {max(alternative['return_point_errors_mm']):.3g} | "
            f"{_gear_sizes(alternative['gears'])} | "
            f"{', '.join(_bound(b) for b in alternative['active_bounds']) or 'none'} | "
            f"{', '.join(map(str, alternative['start_candidates']))}"
            + (f"; then {alternative['restroke']}" if alternative["restroke"] else "") + " |")
    lines += ["", "Lengths in mm; turns are the carrier's, clockwise from pose 1 (deg)."]
    if report["failed"]:
        lines += ["", "Candidates whose refinement failed:", ""]
        lines += [f"- candidate {failure['candidate']}: {failure['reason']}" for failure in report["failed"]]
    return lines


def evaluation_markdown(report: dict, labels: tuple[str, ...]) -> str:
    lines = [f"# Given design {report['source']}", "", "| | " + " | ".join(labels) + " |",
             "|---" * (len(labels) + 1) + "|",
             _row("closest P (mm)", report["key_pose_position_errors_mm"]),
             _row("plate angle there (deg)", report["key_pose_angle_errors_deg"]),
             _row("BE length error (mm)", report["receiving_chain_errors_mm"]),
             _row("AF length error (mm)", report["carrier_chain_errors_mm"]), "",
             "Violations: " + ("; ".join(report["violations"]) or "none"), ""]
    lines += support_markdown(report)
    return "\n".join(lines) + "\n"


def support_markdown(report: dict) -> list[str]:
    """The "Seedling support" section (none without ``[support]``)."""
    if "support" not in report:
        return []
    s = report["support"]
    cam, segments = s["cam"], s["segments"]
    pressure, curvature = cam["max_pressure_angle_deg"], cam["min_curvature_radius_mm"]
    angles = ", ".join(f"{name} {value:.2f}" for name, value in segments["cam_angles_deg"].items())
    return ["## Seedling support (cam and rocker-slider, eq 14-15)", "",
            f"- plate line x_Z = {s['plate_x_mm']:g} mm, heights {s['heights_mm'][0]:g} to {s['heights_mm'][1]:g} mm; "
            f"rocker theta_CG {s['theta_cg_deg']['low']:.3f} to {s['theta_cg_deg']['high']:.3f} deg, swing psi = "
            f"{s['swing_deg']:.3f} deg; bell crank KCG {s['bell_crank_kcg_deg']:.3f} deg",
            f"- clearance to the receiving plate (min x_E - x_Z): {s['clearance_to_receiving_plate_mm']:.3f} mm at "
            f"carrier turn {s['clearance_least_at_carrier_turn_deg']:.1f} deg",
            f"- cam segments (deg of cam; drive ratio {s['drive_ratio']:g}, cam turning with the carrier): {angles}; "
            f"from {segments['source']}",
            f"- cam: base radius {cam['base_radius_mm']:g} mm; largest pressure angle rise "
            f"{pressure['rise']:.3f} deg, return {pressure['return']:.3f} deg (limit {pressure['limit']:g}); smallest "
            f"convex pitch radius {curvature['pitch']:.3f} mm; undercut: {'yes' if cam['undercut'] else 'no'}; "
            f"{len(cam['acceleration_jumps'])} acceleration jumps ({', '.join(cam['laws'])})",
            "- " + ("; ".join(s["failures"]) if s["failures"] else "passes its checks"),
            f"- {table5_line(s['table5'])}", ""]


def table5_line(table5: dict) -> str:
    """One sentence on the published support (Wang et al. 2025, Table 5) as ``cam.table5`` evaluates it."""
    printed, datum = table5["printed"], table5["heights_from_datum"][0]
    lifting = next(c for c in table5["perpendicular_layout"]["cams"] if c["lifts_plate"])
    worst = max(lifting["max_pressure_angle_deg"][k] for k in ("rise", "return"))
    return (f"Table 5 as printed {'assembles' if printed['assembles'] else 'does not assemble'} "
            f"(|CH| {printed['distance_c_to_h_mm'][0]:.2f} / {printed['distance_c_to_h_mm'][1]:.2f} mm against a "
            f"reach of {printed['reach_mm'][0]:g}-{printed['reach_mm'][1]:g} mm); heights from a datum "
            f"y0 = {datum['datum_y0_mm']:.2f} mm give psi = {datum['swing_deg']:.2f} deg; on the square cam layout the "
            f"roller side that lifts the plate ({lifting['roller_side']}) reaches a pressure angle of {worst:.2f} deg "
            f"(docs/cam.md)")

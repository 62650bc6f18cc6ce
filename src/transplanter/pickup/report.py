"""A pick-up report (``PickupResult.to_json``) as Markdown."""
from __future__ import annotations


def to_markdown(report: dict, files: list[str]) -> str:
    carrier, arm = report["carrier"], report["arm"]
    lines = [f"# Pick-up mechanism: {report['title'] or report['source']}", "",
             f"- Carrier L1 = {carrier['first_length_mm']:g} mm, L2 = {carrier['second_length_mm']:g} mm, bend delta0 = "
             f"{carrier['bend_deg']:g} deg, start phi0 = {carrier['start_deg']:g} deg, {carrier['speed_rad_s']:.4f} rad/s "
             "counterclockwise",
             f"- Arm S = {arm['length_mm']:g} mm, mounting alpha0 = {arm['mounting_deg']:g} deg"]
    for k, stage in enumerate(report["stages"], 1):
        lines.append(f"- Stage {k}: {stage['family']} scaled by {stage['scale']:.6f} to close at "
                     f"{stage['center_distance_mm']:.6f} mm (closure error {stage['closure_error_rad']:.1e} rad); "
                     f"ratio {stage['ratio_range'][0]:.4f} to {stage['ratio_range'][1]:.4f}")
    lines += [f"- Planet turn against the carrier from {report['planet_turn_range_deg'][0]:.3f} to "
              f"{report['planet_turn_range_deg'][1]:.3f} deg ({report['planet_turn_per_carrier_turn_deg']:.3f} deg per turn)",
              f"- Tip x {report['tip_x_range_mm'][0]:.3f} to {report['tip_x_range_mm'][1]:.3f} mm, y "
              f"{report['tip_y_range_mm'][0]:.3f} to {report['tip_y_range_mm'][1]:.3f} mm; speed "
              f"{report['tip_speed_range_mm_s'][0]:.3f} to {report['tip_speed_range_mm_s'][1]:.3f} mm/s"]
    for name in ("picking", "pushing"):
        a = report[name]
        lines.append(f"- {name.capitalize()} angle {a['angle_deg']:.3f} deg (needle to the horizontal) at the "
                     f"{a['where'] if isinstance(a['where'], str) else 'given'} point, carrier turn "
                     f"{a['carrier_turn_deg']:.2f} deg, tip ({a['tip_mm'][0]:.3f}, {a['tip_mm'][1]:.3f}) mm")
    if files:
        lines += ["", "Files: " + ", ".join(files)]
    lines += [""] + [f"![{f}]({f})" for f in files if f.endswith(".png")]
    return "\n".join(lines) + "\n"

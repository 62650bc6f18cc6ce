"""A cam report (``CamResult.to_json``) as Markdown."""
from __future__ import annotations


def _number(value, digits=4, unit=""):
    return "none" if value is None else f"{value:.{digits}f}{unit}"


def to_markdown(report: dict, figures: list[str], drawings: list[str]) -> str:
    follower = report["follower"]
    swing = follower["kind"] == "oscillating"
    if follower["kind"] == "flat_faced":
        offsets = follower["face_offset_range_mm"]
        kind = (f"flat-faced translating follower, contact from {offsets[0]:.3f} to {offsets[1]:.3f} mm along the face "
                "(its width must cover this)")
    else:
        where = (f"pivot {follower['pivot_mm']} mm, arm {follower['arm_length_mm']:g} mm, roller {follower['roller_side']}"
                 if swing else f"offset {follower['offset_mm']:g} mm")
        kind = f"{follower['kind']} roller follower, roller radius {follower['roller_radius_mm']:g} mm, {where}"
    pressure, curvature = report["max_pressure_angle_deg"], report["min_curvature_radius_mm"]
    lines = [f"# {report['title'] or report['source']}", "",
             f"- {kind}; cam turning {report['direction']}",
             f"- base radius {report['base_radius_mm']:.6f} mm"
             + (f" (the smallest meeting the limits; {report['cams_evaluated']} cams evaluated)"
                if report["designed_base_radius"] else ""),
             f"- the profile comes within {report['nearest_profile_mm']['distance']:.4f} mm of the centre at "
             f"{report['nearest_profile_mm']['at_deg']:.2f} deg; bore "
             + (f"{report['bore_radius_mm']:g} mm" if report["bore_radius_mm"] is not None else "not given (the drawings "
                "show one of 0.4 of that distance)"),
             "- segments: " + "; ".join(
                 f"{s['kind']} {s['angle_deg']:g} deg" + (f" {s['law']} {s['swing_deg' if swing else 'lift_mm']:g} "
                                                          f"{'deg' if swing else 'mm'}" if s["law"] else "")
                 for s in report["segments"]),
             f"- largest pressure angle: rise {_number(pressure['rise'], 3, ' deg')} at "
             f"{_number(pressure['at_deg']['rise'], 2, ' deg')}, return {_number(pressure['return'], 3, ' deg')} at "
             f"{_number(pressure['at_deg']['return'], 2, ' deg')} (limit {pressure['limit']:g} deg)",
             ("- smallest curvature radius of the profile (R_b + s + s''): "
              f"{_number(curvature['profile'])} mm at {_number(curvature['at_deg']['profile'], 2, ' deg')}"
              if follower["kind"] == "flat_faced" else
              f"- smallest convex curvature radius: pitch curve {_number(curvature['pitch'])} mm at "
              f"{_number(curvature['at_deg']['pitch'], 2, ' deg')}, profile {_number(curvature['profile'])} mm; "
              f"smallest concave profile radius {_number(curvature['concave_profile'])} mm")
             + (f" (limit {curvature['profile_limit']:g} mm)" if curvature["profile_limit"] else ""),
             f"- {'stretches the flat face cannot follow' if follower['kind'] == 'flat_faced' else 'undercut'}: "
             f"{'yes' if report['undercut'] else 'no'}"
             + "".join(f"; {s['from_deg']:.2f}-{s['to_deg']:.2f} deg (radius down to {s['worst_mm']:.4f} mm)"
                       for s in report["undercut_stretches"]),
             "- roller cutting into the profile: " + ("; ".join(
                 f"{s['from_deg']:.2f}-{s['to_deg']:.2f} deg by {s['worst_mm']:.4f} mm"
                 for s in report["roller_interference"]) or "nowhere")]
    if report["acceleration_jumps"]:
        lines.append(f"- acceleration jumps (laws {', '.join(report['laws_with_acceleration_jumps'])}; finite jumps "
                     "mean infinite jerk, a knock at speed): " + "; ".join(
                         f"at {j['at_deg']:.2f} deg between {j['between'][0]} and {j['between'][1]}: "
                         f"{j['size']:+.6g} {j['unit']}" for j in report["acceleration_jumps"]))
    else:
        lines.append("- acceleration continuous between segments")
    if drawings:
        lines += ["", "Drawings: " + ", ".join(drawings)]
    lines += [""] + [f"![{f}]({f})" for f in figures]
    return "\n".join(lines) + "\n"

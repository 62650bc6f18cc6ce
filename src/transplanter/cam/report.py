"""A cam as JSON (report.json) and Markdown (report.md)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from transplanter.cam.checks import Extreme, Stretch
from transplanter.cam.solid_files import solids_note

if TYPE_CHECKING:
    from transplanter.cam.result import CamResult


def _value(extreme: Extreme | None, scale=float) -> float | None:
    return None if extreme is None else float(scale(extreme.value))


def _at(extreme: Extreme | None) -> float | None:
    return None if extreme is None else float(np.degrees(extreme.angle))


def _stretch(stretch: Stretch) -> dict:
    return {"from_deg": float(np.degrees(stretch.start)), "to_deg": float(np.degrees(stretch.end)),
            "worst_mm": stretch.worst}


def _finite(value: float | None) -> float | None:
    return None if value is None or not np.isfinite(value) else float(value)


def _segment_name(result: CamResult, index: int) -> str:
    segment = result.problem.segments[index]
    return f"{index + 1}: {segment.kind}" + (f" ({segment.law})" if segment.law else "")


def _unit(result: CamResult):
    """Lifts and swings as reported: degrees for an oscillating follower, mm otherwise."""
    return np.degrees if result.problem.oscillating else float


def _lift(result: CamResult, lift: float) -> float:
    return round(float(_unit(result)(abs(lift))), 9)


def _pressure_limit_deg(result: CamResult) -> float:
    return round(float(np.degrees(result.problem.pressure_limit)), 9)


def _face_offsets(result: CamResult) -> list[float]:
    """A flat face's contact from the follower's line (mm), least and most."""
    return [float(result.geometry.center[:, 0].min()), float(result.geometry.center[:, 0].max())]


def _laws_with_jumps(result: CamResult) -> list[str]:
    """The laws of the segments on either side of an acceleration jump."""
    segments = result.problem.segments
    return sorted({law for j in result.checks.acceleration_jumps for k in (j.before, j.after)
                   if (law := segments[k].law)})


def cam_result_json(result: CamResult) -> dict:
    """The report as plain JSON types (mm and degrees; a swing in degrees): the content of report.json."""
    problem, checks, follower = result.problem, result.checks, result.problem.follower
    swing, flat = problem.oscillating, follower.kind == "flat_faced"
    unit = _unit(result)
    jumps = [{"at_deg": round(float(np.degrees(j.angle)), 9),
              "between": [_segment_name(result, j.before), _segment_name(result, j.after)],
              "size": float(unit(j.size)), "unit": "deg/rad^2" if swing else "mm/rad^2"}
             for j in checks.acceleration_jumps]
    return {
        "source": problem.source, "title": problem.title,
        "follower": {"kind": follower.kind, "roller_radius_mm": follower.roller_radius,
                     **({"pivot_mm": follower.arm[0].tolist(), "arm_length_mm": follower.arm[1],
                         "roller_side": "pulled" if follower.pulled else "pushed"} if swing
                        else {"face_offset_range_mm": _face_offsets(result)} if flat
                        else {"offset_mm": follower.offset})},
        "direction": "counterclockwise" if problem.direction > 0 else "clockwise",
        "base_radius_mm": result.base_radius,
        "bore_radius_mm": problem.bore_radius,
        "solids": solids_note(result),
        "nearest_profile_mm": {"distance": result.nearest_profile.value, "at_deg": _at(result.nearest_profile)},
        "designed_base_radius": result.designed,
        "cams_evaluated": result.cams_evaluated,
        "segments": [{"kind": s.kind, "angle_deg": round(float(np.degrees(s.angle)), 9), "law": s.law,
                      ("swing_deg" if swing else "lift_mm"): _lift(result, s.lift)} for s in problem.segments],
        "laws": sorted({s.law for s in problem.segments if s.law}),
        "max_pressure_angle_deg": {"rise": _value(checks.pressure["rise"], np.degrees),
                                   "return": _value(checks.pressure["return"], np.degrees),
                                   "at_deg": {"rise": _at(checks.pressure["rise"]),
                                              "return": _at(checks.pressure["return"])},
                                   "limit": _pressure_limit_deg(result)},
        "min_curvature_radius_mm": {"pitch": _value(checks.min_pitch_radius),
                                    "profile": _value(checks.min_profile_radius),
                                    "concave_profile": _finite(_value(checks.min_concave_profile_radius)),
                                    "profile_limit": problem.profile_radius_limit,
                                    "at_deg": {"pitch": _at(checks.min_pitch_radius),
                                               "profile": _at(checks.min_profile_radius),
                                               "concave_profile": _at(checks.min_concave_profile_radius)}},
        "undercut": bool(checks.undercut),
        "undercut_stretches": [_stretch(s) for s in checks.undercut],
        "roller_interference": [_stretch(s) for s in checks.interference],
        "acceleration_jumps": jumps,
        "laws_with_acceleration_jumps": _laws_with_jumps(result),
        "displacement_range": [float(unit(result.geometry.motion[0].min())),
                               float(unit(result.geometry.motion[0].max()))],
        "samples": int(result.geometry.angle.size),
        "timings_s": result.timings_s,
    }


def _number(value: float | None, digits: int = 4, unit: str = "") -> str:
    return "none" if value is None else f"{value:.{digits}f}{unit}"


def _degrees(stretch: Stretch) -> str:
    return f"{np.degrees(stretch.start):.2f}-{np.degrees(stretch.end):.2f} deg"


def _follower_line(result: CamResult) -> str:
    follower = result.problem.follower
    if follower.kind == "flat_faced":
        low, high = _face_offsets(result)
        return (f"flat-faced translating follower, contact from {low:.3f} to {high:.3f} mm along the face "
                "(its width must cover this)")
    where = (f"pivot {follower.arm[0].tolist()} mm, arm {follower.arm[1]:g} mm, roller "
             f"{'pulled' if follower.pulled else 'pushed'}" if result.problem.oscillating
             else f"offset {follower.offset:g} mm")
    return f"{follower.kind} roller follower, roller radius {follower.roller_radius:g} mm, {where}"


def _segment_text(result: CamResult) -> str:
    swing = result.problem.oscillating
    return "; ".join(f"{s.kind} {round(float(np.degrees(s.angle)), 9):g} deg"
                     + (f" {s.law} {_lift(result, s.lift):g} {'deg' if swing else 'mm'}" if s.law else "")
                     for s in result.problem.segments)


def _curvature_line(result: CamResult) -> str:
    checks, limit = result.checks, result.problem.profile_radius_limit
    if result.problem.follower.kind == "flat_faced":
        profile = checks.min_profile_radius
        line = ("- smallest curvature radius of the profile (R_b + s + s''): "
                f"{_number(_value(profile))} mm at {_number(_at(profile), 2, ' deg')}")
    else:
        pitch, profile, concave = checks.min_pitch_radius, checks.min_profile_radius, checks.min_concave_profile_radius
        line = (f"- smallest convex curvature radius: pitch curve {_number(_value(pitch))} mm at "
                f"{_number(_at(pitch), 2, ' deg')}, profile {_number(_value(profile))} mm; smallest concave profile "
                f"radius {_number(_finite(_value(concave)))} mm")
    return line + (f" (limit {limit:g} mm)" if limit else "")


def to_markdown(result: CamResult, files: Sequence[str] = ()) -> str:
    """report.md: the follower, the motion, every check and where, the drawings and figures among ``files``."""
    problem, checks = result.problem, result.checks
    flat = problem.follower.kind == "flat_faced"
    rise, back = checks.pressure["rise"], checks.pressure["return"]
    nearest, turning = result.nearest_profile, "counterclockwise" if problem.direction > 0 else "clockwise"
    designed = f" (the smallest meeting the limits; {result.cams_evaluated} cams evaluated)" if result.designed else ""
    lines = [f"# {problem.title or problem.source}", "",
             f"- {_follower_line(result)}; cam turning {turning}",
             f"- base radius {result.base_radius:.6f} mm{designed}",
             f"- the profile comes within {nearest.value:.4f} mm of the centre at {_at(nearest):.2f} deg; bore "
             + (f"{problem.bore_radius:g} mm" if problem.bore_radius is not None else "not given (the drawings "
                "show one of 0.4 of that distance)"),
             "- segments: " + _segment_text(result),
             f"- largest pressure angle: rise {_number(_value(rise, np.degrees), 3, ' deg')} at "
             f"{_number(_at(rise), 2, ' deg')}, return {_number(_value(back, np.degrees), 3, ' deg')} at "
             f"{_number(_at(back), 2, ' deg')} (limit {_pressure_limit_deg(result):g} deg)",
             _curvature_line(result),
             f"- {'stretches the flat face cannot follow' if flat else 'undercut'}: "
             f"{'yes' if checks.undercut else 'no'}"
             + "".join(f"; {_degrees(s)} (radius down to {s.worst:.4f} mm)" for s in checks.undercut),
             "- roller cutting into the profile: "
             + ("; ".join(f"{_degrees(s)} by {s.worst:.4f} mm" for s in checks.interference) or "nowhere")]
    if checks.acceleration_jumps:
        swing = problem.oscillating
        lines.append(f"- acceleration jumps (laws {', '.join(_laws_with_jumps(result))}; finite jumps "
                     "mean infinite jerk, a knock at speed): " + "; ".join(
                         f"at {round(float(np.degrees(j.angle)), 9):.2f} deg between {_segment_name(result, j.before)} "
                         f"and {_segment_name(result, j.after)}: {float(_unit(result)(j.size)):+.6g} "
                         f"{'deg/rad^2' if swing else 'mm/rad^2'}" for j in checks.acceleration_jumps))
    else:
        lines.append("- acceleration continuous between segments")
    lines.append(f"- {solids_note(result)}")
    drawings = [name for name in files if not name.endswith(".png")]
    if drawings:
        lines += ["", "Drawings: " + ", ".join(drawings)]
    lines += [""] + [f"![{f}]({f})" for f in files if f.endswith(".png")]
    return "\n".join(lines) + "\n"

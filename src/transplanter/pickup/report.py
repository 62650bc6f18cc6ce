"""A pick-up mechanism as JSON (report.json) and Markdown (report.md)."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from transplanter.pickup.result import NeedleAngle, PickupResult


def _where(where: str | float) -> str | float:
    """Where the needle is read: "farthest", "lowest", or the carrier turn given (deg)."""
    return where if isinstance(where, str) else float(np.degrees(where))


def needle_json(where: str | float, needle: NeedleAngle) -> dict:
    return {"where": _where(where), "angle_deg": float(np.degrees(needle.angle)),
            "carrier_turn_deg": float(np.degrees(needle.carrier_turn)), "tip_mm": needle.tip.tolist(),
            "needle_direction_deg": float(np.degrees(np.mod(needle.direction, 2 * np.pi)))}


def _ranges(result: PickupResult) -> dict[str, tuple[float, float]]:
    """Least and most of the planet's turn (deg), the tip's x and y (mm) and its speed (mm/s) over the turn."""
    speed = np.hypot(*result.velocity.T)
    return {"planet_turn": (float(np.degrees(result.planet_turn.min())), float(np.degrees(result.planet_turn.max()))),
            "x": (float(result.tip[:, 0].min()), float(result.tip[:, 0].max())),
            "y": (float(result.tip[:, 1].min()), float(result.tip[:, 1].max())),
            "speed": (float(speed.min()), float(speed.max()))}


def pickup_result_json(result: PickupResult) -> dict:
    """The report as plain JSON types (mm, degrees, mm/s): the content of report.json."""
    p, ranges = result.problem, _ranges(result)
    return {
        "source": p.source, "title": p.title,
        "carrier": {"first_length_mm": p.first_length, "second_length_mm": p.second_length,
                    "bend_deg": float(np.degrees(p.bend)), "start_deg": float(np.degrees(p.start)),
                    "speed_rad_s": p.speed},
        "arm": {"length_mm": p.arm_length, "mounting_deg": float(np.degrees(p.mounting))},
        "stages": [{"family": s.driver.family, "scale": s.driver.scale, "center_distance_mm": s.center_distance,
                    "closure_error_rad": s.closure_error, "ratio_range": [float(s.ratio.min()), float(s.ratio.max())]}
                   for s in (result.stage_one, result.stage_two)],
        "planet_turn_range_deg": list(ranges["planet_turn"]),
        "planet_turn_per_carrier_turn_deg": float(np.degrees(result.planet_turn_per_turn)),
        "tip_x_range_mm": list(ranges["x"]),
        "tip_y_range_mm": list(ranges["y"]),
        "picking": needle_json(p.picking, result.picking),
        "pushing": needle_json(p.pushing, result.pushing),
        "tip_speed_range_mm_s": list(ranges["speed"]),
        "timings_s": result.timings_s,
    }


def to_markdown(result: PickupResult, files: Sequence[str] = ()) -> str:
    """report.md: the carrier, the arm, both stages, the tip's path and speed, the needle's angles, ``files``."""
    p, ranges = result.problem, _ranges(result)
    lines = [f"# Pick-up mechanism: {p.title or p.source}", "",
             f"- Carrier L1 = {p.first_length:g} mm, L2 = {p.second_length:g} mm, bend delta0 = "
             f"{np.degrees(p.bend):g} deg, start phi0 = {np.degrees(p.start):g} deg, {p.speed:.4f} rad/s "
             "counterclockwise",
             f"- Arm S = {p.arm_length:g} mm, mounting alpha0 = {np.degrees(p.mounting):g} deg"]
    for k, stage in enumerate((result.stage_one, result.stage_two), 1):
        lines.append(f"- Stage {k}: {stage.driver.family} scaled by {stage.driver.scale:.6f} to close at "
                     f"{stage.center_distance:.6f} mm (closure error {stage.closure_error:.1e} rad); "
                     f"ratio {stage.ratio.min():.4f} to {stage.ratio.max():.4f}")
    (turn_low, turn_high), (x_low, x_high), (y_low, y_high), (slow, fast) = ranges.values()
    lines += [f"- Planet turn against the carrier from {turn_low:.3f} to {turn_high:.3f} deg "
              f"({np.degrees(result.planet_turn_per_turn):.3f} deg per turn)",
              f"- Tip x {x_low:.3f} to {x_high:.3f} mm, y {y_low:.3f} to {y_high:.3f} mm; speed {slow:.3f} to "
              f"{fast:.3f} mm/s"]
    for name, where, needle in (("Picking", p.picking, result.picking), ("Pushing", p.pushing, result.pushing)):
        lines.append(f"- {name} angle {np.degrees(needle.angle):.3f} deg (needle to the horizontal) at the "
                     f"{where if isinstance(where, str) else 'given'} point, carrier turn "
                     f"{np.degrees(needle.carrier_turn):.2f} deg, tip ({needle.tip[0]:.3f}, {needle.tip[1]:.3f}) mm")
    if files:
        lines += ["", "Files: " + ", ".join(files)]
    lines += [""] + [f"![{f}]({f})" for f in files if f.endswith(".png")]
    return "\n".join(lines) + "\n"

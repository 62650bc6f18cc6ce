"""A pick-up mechanism turned through one carrier turn, and its JSON (the content of report.json).

Picking and pushing angles: the acute angle (deg) between the needle, the line O2 -> Q of the arm,
and the horizontal, where the needle picks (by default the tip's farthest point from O, where it
reaches into the tray) and where it pushes (by default the tip's lowest point). The cusp-pitch-curve
paper measures them on its Figure 18 (44.7 and 70.2 deg on its prototype) without printing how or its Table 1
values, so its numbers cannot be recomputed; this reading is the package's.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.gears.pair import GearPairDesign
from transplanter.pickup.problem import PickupProblem


@dataclass(frozen=True)
class PickupResult:
    """Tip path (mm) and velocity (mm/s) at carrier turns ``carrier_turns`` (rad, counterclockwise from the
    start); ``planet_turn`` psi (rad) against the carrier and its rate per carrier turn."""

    problem: PickupProblem
    stage_one: GearPairDesign
    stage_two: GearPairDesign
    carrier_turns: np.ndarray
    planet_turn: np.ndarray
    tip: np.ndarray
    velocity: np.ndarray
    planet_rate: np.ndarray
    planet_turn_per_turn: float       # psi after one whole carrier turn (rad): -2 pi when both stages close
    timings_s: dict

    def needle_direction(self) -> np.ndarray:
        """Angle (rad) of the needle O2 -> Q from +x at each carrier turn."""
        p = self.problem
        return p.start + self.carrier_turns + p.bend + self.planet_turn + p.mounting

    def _index(self, where) -> int:
        if where == "farthest":
            return int(np.argmax(np.hypot(*self.tip.T)))
        if where == "lowest":
            return int(np.argmin(self.tip[:, 1]))
        return int(np.argmin(np.abs(np.mod(self.carrier_turns - where + np.pi, 2 * np.pi) - np.pi)))

    def angle_at(self, where) -> dict:
        """Needle angle from the horizontal (acute, deg) and where: carrier turn (deg) and tip (mm)."""
        k = self._index(where)
        direction = self.needle_direction()[k]
        acute = np.degrees(abs(np.arctan(np.tan(direction))))
        return {"angle_deg": float(acute), "carrier_turn_deg": float(np.degrees(self.carrier_turns[k])),
                "tip_mm": self.tip[k].tolist(), "needle_direction_deg": float(np.degrees(np.mod(direction, 2 * np.pi)))}

    @property
    def closure_errors(self) -> list[float]:
        return [self.stage_one.closure_error, self.stage_two.closure_error]

    def to_json(self) -> dict:
        p = self.problem
        speed = np.hypot(*self.velocity.T)
        return {
            "source": p.source, "title": p.title,
            "carrier": {"first_length_mm": p.first_length, "second_length_mm": p.second_length,
                        "bend_deg": float(np.degrees(p.bend)), "start_deg": float(np.degrees(p.start)),
                        "speed_rad_s": p.speed},
            "arm": {"length_mm": p.arm_length, "mounting_deg": float(np.degrees(p.mounting))},
            "stages": [{"family": s.driver.family, "scale": s.driver.scale, "center_distance_mm": s.center_distance,
                        "closure_error_rad": s.closure_error,
                        "ratio_range": [float(s.ratio.min()), float(s.ratio.max())]}
                       for s in (self.stage_one, self.stage_two)],
            "planet_turn_range_deg": [float(np.degrees(self.planet_turn.min())),
                                      float(np.degrees(self.planet_turn.max()))],
            "planet_turn_per_carrier_turn_deg": float(np.degrees(self.planet_turn_per_turn)),
            "tip_x_range_mm": [float(self.tip[:, 0].min()), float(self.tip[:, 0].max())],
            "tip_y_range_mm": [float(self.tip[:, 1].min()), float(self.tip[:, 1].max())],
            "picking": {"where": p.picking if isinstance(p.picking, str) else float(np.degrees(p.picking)),
                        **self.angle_at(p.picking)},
            "pushing": {"where": p.pushing if isinstance(p.pushing, str) else float(np.degrees(p.pushing)),
                        **self.angle_at(p.pushing)},
            "tip_speed_range_mm_s": [float(speed.min()), float(speed.max())],
            "timings_s": self.timings_s,
        }

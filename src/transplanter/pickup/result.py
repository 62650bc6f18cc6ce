"""A pick-up mechanism turned through one carrier turn, and the checks it passes.

Picking and pushing angles: the acute angle (deg) between the needle, the line O2 -> Q of the arm,
and the horizontal, where the needle picks (by default the tip's farthest point from O, where it
reaches into the tray) and where it pushes (by default the tip's lowest point). The cusp-pitch-curve
paper measures them on its Figure 18 (44.7 and 70.2 deg on its prototype) without printing how or its Table 1
values, so its numbers cannot be recomputed; this reading is the package's.

Checks (``failures``), each relative to the mechanism's reach L1 + L2 + S: both gear stages close (the
driven gear's miss after one driver turn, as arc at the stage's centre distance, within
``CLOSURE_TOLERANCE`` of the reach), and the tip path is reached over the whole turn (tip and velocity
finite at every carrier position, and the planet back at its start after one carrier turn, one turn
against the carrier as the train demands, within ``CLOSURE_TOLERANCE`` of the reach as arc at the tip).
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from transplanter import progress
from transplanter.command_result import CommandResult
from transplanter.gears.pair import GearPairDesign
from transplanter.pickup.problem import PickupProblem

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer

#: Closure of each stage and of the tip after one carrier turn, per mm of the reach L1 + L2 + S (the gears close
#: to 1e-15 rad, about 1e-13 mm on the bundled example; ``gears.pair`` refuses a pair beyond 1e-6 rad).
CLOSURE_TOLERANCE = 1e-8


@dataclass(frozen=True)
class NeedleAngle:
    """The needle at one carrier position: ``angle`` to the horizontal (rad, acute), the carrier turn (rad),
    the tip (mm), the needle's direction (rad from +x), and the sample ``index``."""

    index: int
    angle: float
    carrier_turn: float
    tip: np.ndarray
    direction: float


@dataclass(frozen=True)
class PickupResult(CommandResult):
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

    @property
    def source(self) -> str:
        return self.problem.source

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

    def angle_at(self, where) -> NeedleAngle:
        """The needle where the tip is farthest from O (``"farthest"``), lowest (``"lowest"``), or at a carrier
        turn (rad)."""
        k = self._index(where)
        direction = float(self.needle_direction()[k])
        return NeedleAngle(k, float(abs(np.arctan(np.tan(direction)))), float(self.carrier_turns[k]), self.tip[k],
                           direction)

    @property
    def picking(self) -> NeedleAngle:
        return self.angle_at(self.problem.picking)

    @property
    def pushing(self) -> NeedleAngle:
        return self.angle_at(self.problem.pushing)

    @property
    def closure_errors(self) -> list[float]:
        return [self.stage_one.closure_error, self.stage_two.closure_error]

    @property
    def reach(self) -> float:
        """L1 + L2 + S (mm): the farthest the tip can be from O, the size the checks are relative to."""
        p = self.problem
        return p.first_length + p.second_length + p.arm_length

    @property
    def failures(self) -> list[str]:
        """The checks of the module docstring that fail."""
        tolerance, found = CLOSURE_TOLERANCE * self.reach, []
        for name, stage in (("stage1", self.stage_one), ("stage2", self.stage_two)):
            miss = abs(stage.closure_error) * stage.center_distance
            if not miss <= tolerance:
                found.append(f"{name} does not close: its driven gear turns {np.degrees(stage.closure_error):+.3g} deg "
                             f"away from a whole turn per driver turn, {miss:.3g} mm at its centre distance "
                             f"{stage.center_distance:.6g} mm (more than {CLOSURE_TOLERANCE:g} of the reach "
                             f"L1 + L2 + S = {self.reach:.6g} mm)")
        lost = ~(np.isfinite(self.tip).all(axis=1) & np.isfinite(self.velocity).all(axis=1))
        if lost.any():
            found.append(f"the tip path is not reached at {int(lost.sum())} of {lost.size} carrier positions, first at "
                         f"carrier turn {np.degrees(self.carrier_turns[lost][0]):.2f} deg (tip or velocity not finite)")
        off = self.planet_turn_per_turn + 2 * np.pi
        if not self.problem.arm_length * abs(off) <= tolerance:
            found.append(f"the planet turns {np.degrees(self.planet_turn_per_turn):.6g} deg against the carrier per "
                         f"carrier turn, not -360: after a turn the needle is {np.degrees(off):+.3g} deg off its "
                         f"start, {self.problem.arm_length * abs(off):.3g} mm of arc at the tip (more than "
                         f"{CLOSURE_TOLERANCE:g} of the reach L1 + L2 + S = {self.reach:.6g} mm)")
        return found

    def to_json(self) -> dict[str, Any]:
        from transplanter.pickup.report import pickup_result_json

        return pickup_result_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.pickup.report import to_markdown

        return to_markdown(self, files)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.pickup.figures import figure_drawers

        return figure_drawers(self)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """``pickup.gif``, one carrier turn (``pickup.write_animation``), unless ``animation`` is False."""
        if not animation:
            return []
        from transplanter.pickup.animation import write_animation

        with progress.step("animation"):
            return [write_animation(self, folder)]

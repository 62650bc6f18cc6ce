"""A gear on a sheet: any gear given its outline, pitch curve, keyed bore and assembly mark, in its own frame
(centre at the origin), millimetres."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from transplanter.drawing.sheet import Sheet, TitleBlock
from transplanter.drawing.svg import write_svg
from transplanter.shafts.keyed_bore import KeyedBore

#: The assembly mark runs from the keyway's bottom out to this fraction of the root radius.
MARK_REACH = 0.9
#: Centre lines span this many bore diameters.
CROSS_DIAMETERS = 2.5


@dataclass(frozen=True)
class GearDrawing:
    """One gear to make: ``outline`` (N, 2) closed tooth outline (or pitch curve for an uncut gear),
    ``pitch_curve`` (M, 2), ``bore`` with its keyway on the assembly mark's direction (towards the contact point
    at the assembly pose), and the title block."""

    name: str
    outline: np.ndarray
    pitch_curve: np.ndarray
    bore: KeyedBore
    title: TitleBlock

    @property
    def root_radius(self) -> float:
        """The outline's smallest distance from the centre (mm)."""
        return float(np.linalg.norm(self.outline, axis=1).min())

    @property
    def mark(self) -> np.ndarray:
        """The assembly mark (2, 2): from the keyway's bottom towards the contact point, short of the root."""
        unit = np.array([np.cos(self.bore.direction), np.sin(self.bore.direction)])
        return np.outer([self.bore.reach, max(MARK_REACH * self.root_radius, self.bore.reach)], unit)


def draw_keyed_bore(sheet: Sheet, bore: KeyedBore, center=(0.0, 0.0), turn: float = 0.0) -> None:
    """The bore's circle (BORE, an arc round to the keyway) and its keyway (KEYWAY), turned by ``turn`` (rad)
    about the part's centre and moved to ``center``."""
    center = np.asarray(center, float)
    direction = np.degrees(bore.direction + turn)
    half = np.degrees(bore.half_angle)
    sheet.arc(center, bore.radius, direction + half, direction + 360 - half, "BORE")
    cos, sin = np.cos(turn), np.sin(turn)
    sheet.polyline(center + bore.keyway() @ np.array([[cos, sin], [-sin, cos]]), "KEYWAY")


def gear_sheet(gear: GearDrawing) -> Sheet:
    """Outline, pitch curve, keyed bore, mark, centre lines, the bore's diameter and d + t2, and the title."""
    sheet = Sheet()
    sheet.polyline(gear.outline, "OUTLINE", close=True)
    sheet.polyline(gear.pitch_curve, "PITCH")
    draw_keyed_bore(sheet, gear.bore)
    sheet.line(gear.mark[0], gear.mark[1], "MARK")
    sheet.center_cross((0.0, 0.0), CROSS_DIAMETERS * gear.bore.diameter)
    unit = np.array([np.cos(gear.bore.direction), np.sin(gear.bore.direction)])
    sheet.diameter_dimension((0.0, 0.0), gear.bore.radius, np.degrees(gear.bore.direction) + 135)
    sheet.aligned_dimension(-gear.bore.radius * unit, gear.bore.reach * unit, gear.bore.key.width)
    sheet.title_block(gear.title)
    return sheet


def write_gear_sheet(gear: GearDrawing, folder: Path) -> tuple[Sheet, list[Path]]:
    """``<name>.dxf`` and ``<name>.svg`` of ``gear`` in ``folder``: the sheet (for the PDF) and the files."""
    sheet, dxf, svg = gear_sheet(gear), folder / f"{gear.name}.dxf", folder / f"{gear.name}.svg"
    sheet.save(dxf)
    write_svg(gear.outline, svg, pitch_curve=gear.pitch_curve, bore=gear.bore.outline(), mark=gear.mark)
    return sheet, [dxf, svg]


def write_gear_sheets(gears, folder: Path) -> list[Path]:
    """``<name>.dxf`` and ``<name>.svg`` per ``GearDrawing`` in ``folder``; the files written."""
    return [path for gear in gears for path in write_gear_sheet(gear, folder)[1]]

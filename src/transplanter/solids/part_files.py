"""``<part>.step`` per gear and link plate, the one writer of every command that draws parts, and the line its
report gives: the solids' sizes, or that the optional extra transplanter[cad] is missing."""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from transplanter.drawing.gear_sheet import GearDrawing
from transplanter.drawing.plate_sheet import PlatePart
from transplanter.solids.step import MISSING_NOTE, cad_installed, gear_solid, plate_solid, write_step


def write_part_solids(folder: Path, *, gears: Sequence[GearDrawing] = (), face_width: float = 0.0,
                      plates: Sequence[PlatePart] = (), thickness: float = 0.0) -> list[Path]:
    """``<name>.step`` in ``folder`` per link plate (``thickness`` mm thick), then per gear (any outline and keyed
    bore a drawing takes, ``face_width`` mm wide); none without the extra. The files written."""
    if not cad_installed():
        return []
    written = [write_step(plate_solid(part, thickness), folder / f"{part.name}.step") for part in plates]
    written += [write_step(gear_solid(gear, face_width), folder / f"{gear.name}.step") for gear in gears]
    return written


def solids_note(face_width: float, thickness: float | None = None) -> str:
    """One line for a report: the gears' face width and, with plates, their thickness (mm), or why no solids."""
    if not cad_installed():
        return MISSING_NOTE
    plates = "" if thickness is None else f", plates {thickness:g} mm thick"
    return f"STEP solids: gears {face_width:g} mm wide{plates}"

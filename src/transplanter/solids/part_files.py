"""``<part>.step`` per gear, link plate and cam disc, the one writer of every command that draws parts, and the line
its report gives: the solids' sizes, or that the optional extra transplanter[cad] is missing."""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from transplanter.drawing.gear_sheet import GearDrawing
from transplanter.drawing.plate_sheet import PlatePart
from transplanter.solids.step import (
    MISSING_NOTE,
    BoredDisc,
    cad_installed,
    disc_solid,
    gear_solid,
    plate_solid,
    write_step,
)


def write_part_solids(folder: Path, *, gears: Sequence[GearDrawing] = (), face_width: float = 0.0,
                      module: float | None = None, plates: Sequence[PlatePart] = (), thickness: float = 0.0,
                      discs: Sequence[BoredDisc] = ()) -> list[Path]:
    """``<name>.step`` in ``folder`` per link plate and per disc (``thickness`` mm thick), then per gear (any outline
    and keyed bore a drawing takes, ``face_width`` mm wide, its edge within ``solids.step.GEAR_WITHIN_MODULES`` of
    the ``module``, which gears need); none without the extra. The files written."""
    if not cad_installed():
        return []
    written = [write_step(plate_solid(part, thickness), folder / f"{part.name}.step") for part in plates]
    written += [write_step(disc_solid(disc, thickness), folder / f"{disc.name}.step") for disc in discs]
    if gears:
        assert module is not None and module > 0, "a gear's solid is fitted within a part of its module"
        written += [write_step(gear_solid(gear, face_width, module), folder / f"{gear.name}.step") for gear in gears]
    return written


def solids_note(face_width: float | None, thickness: float | None = None, flat_parts: str = "plates") -> str:
    """One line for a report: the gears' face width and the thickness of the ``flat_parts`` (mm), each where there
    are such parts, or why no solids."""
    if not cad_installed():
        return MISSING_NOTE
    sizes = [] if face_width is None else [f"gears {face_width:g} mm wide"]
    sizes += [] if thickness is None else [f"{flat_parts} {thickness:g} mm thick"]
    return "STEP solids: " + ", ".join(sizes)

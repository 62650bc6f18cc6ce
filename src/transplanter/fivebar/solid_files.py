"""The five-bar's parts as STEP solids (``solids.step``): ``<part>.step`` per link plate and gear, when the
optional extra transplanter[cad] is installed."""
from __future__ import annotations

from pathlib import Path

from transplanter.fivebar.drawings import gear_drawings, parts
from transplanter.fivebar.gears_on_carrier import tooth_outlines
from transplanter.fivebar.result import FiveBarResult
from transplanter.solids.step import (
    FACE_WIDTH_MODULES,
    MISSING_NOTE,
    PLATE_THICKNESS_PIN_DIAMETERS,
    cad_installed,
    gear_solid,
    plate_solid,
    write_step,
)


def solid_sizes(result: FiveBarResult) -> dict[str, float]:
    """Gear face width and plate thickness (mm) by the defaults of ``solids.step``."""
    return {"face_width_mm": FACE_WIDTH_MODULES * result.toothed.module,
            "plate_thickness_mm": PLATE_THICKNESS_PIN_DIAMETERS * result.shafts.shafts["hinge"].diameter}


def solids_note(result: FiveBarResult) -> str:
    """One line for the report: the solids' sizes, or why there are none."""
    if not cad_installed():
        return MISSING_NOTE
    sizes = solid_sizes(result)
    return (f"STEP solids: gears {sizes['face_width_mm']:g} mm wide, plates {sizes['plate_thickness_mm']:g} mm "
            "thick")


def write_solids(result: FiveBarResult, folder: Path) -> list[Path]:
    """``<part>.step`` per link plate and gear in ``folder``; none without the extra."""
    if not cad_installed():
        return []
    sizes = solid_sizes(result)
    written = [write_step(plate_solid(part, sizes["plate_thickness_mm"]), folder / f"{part.name}.step")
               for part in parts(result)]
    written += [write_step(gear_solid(gear, sizes["face_width_mm"]), folder / f"{gear.name}.step")
                for gear in gear_drawings(result, tooth_outlines(result.toothed))]
    return written

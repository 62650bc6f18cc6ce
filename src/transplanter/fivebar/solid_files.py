"""The five-bar's parts as STEP solids (``solids.part_files``): ``<part>.step`` per link plate and gear, when the
optional extra transplanter[cad] is installed, sized by the problem's ``solid_sizes``."""
from __future__ import annotations

from pathlib import Path

from transplanter.fivebar.drawings import gear_drawings, parts
from transplanter.fivebar.gears_on_carrier import cut_outlines
from transplanter.fivebar.result import FiveBarResult
from transplanter.solids.part_files import solids_note as part_solids_note
from transplanter.solids.part_files import write_part_solids


def solid_sizes(result: FiveBarResult) -> dict[str, float]:
    """Gear face width and plate thickness (mm): the problem's, else the rules of ``solids.sizes``."""
    sizes = result.problem.solid_sizes
    return {"face_width_mm": sizes.face_width(result.toothed.module),
            "plate_thickness_mm": sizes.thickness(result.shafts.shafts["hinge"].diameter)}


def solids_note(result: FiveBarResult) -> str:
    """One line for the report: the solids' sizes, or why there are none."""
    sizes = solid_sizes(result)
    return part_solids_note(sizes["face_width_mm"], sizes["plate_thickness_mm"])


def write_solids(result: FiveBarResult, folder: Path) -> list[Path]:
    """``<part>.step`` per link plate and gear (made from its cut outline) in ``folder``; none without the extra."""
    sizes = solid_sizes(result)
    return write_part_solids(folder, gears=gear_drawings(result, cut_outlines(result.toothed)),
                             face_width=sizes["face_width_mm"], module=result.toothed.module, plates=parts(result),
                             thickness=sizes["plate_thickness_mm"])

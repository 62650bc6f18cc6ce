"""A cut gear pair's STEP solids (``solids.part_files``): ``driver.step`` and ``driven.step``, the drawings' cut
tooth outlines (as smooth curves, ``solids.step``) and keyed bores extruded to the face width, when the optional
extra transplanter[cad] is installed."""
from __future__ import annotations

from pathlib import Path

from transplanter.gears.drawings import gear_drawings
from transplanter.gears.result import GearResult
from transplanter.solids.part_files import solids_note as part_solids_note
from transplanter.solids.part_files import write_part_solids
from transplanter.solids.sizes import SolidSizes


def solids_note(result: GearResult, sizes: SolidSizes) -> str | None:
    """One line for the report: the gears' face width, or why there are no solids; None before teeth are cut."""
    if result.teeth is None or result.problem.module is None:
        return None
    return part_solids_note(sizes.face_width(result.problem.module))


def write_solids(result: GearResult, folder: Path, sizes: SolidSizes) -> list[Path]:
    """``driver.step`` and ``driven.step`` in ``folder`` once teeth are cut, ``sizes.face_width`` wide; none
    without teeth or without the extra."""
    module = result.problem.module
    if result.teeth is None or module is None:
        return []
    return write_part_solids(folder, gears=gear_drawings(result), face_width=sizes.face_width(module), module=module)

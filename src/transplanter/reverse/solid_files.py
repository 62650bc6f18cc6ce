"""The reverse train's gears as STEP solids (``solids.part_files``): ``<gear>.step`` per gear of its drawings
(``reverse.gear_files``), extruded to the problem's ``train.face_width_mm``, when the optional extra
transplanter[cad] is installed."""
from __future__ import annotations

from pathlib import Path

from transplanter.fivebar.gears_on_carrier import cut_outlines
from transplanter.reverse.gear_files import gear_drawings
from transplanter.reverse.problem import ReverseProblem
from transplanter.solids.part_files import solids_note as part_solids_note
from transplanter.solids.part_files import write_part_solids
from transplanter.trains.toothed_train import ToothedTrain


def solids_note(toothed: ToothedTrain, problem: ReverseProblem) -> str:
    """One line for the report: the gears' face width, or why there are no solids."""
    return part_solids_note(problem.solid_sizes.face_width(toothed.module))


def write_solids(toothed: ToothedTrain, problem: ReverseProblem, folder: Path) -> list[Path]:
    """``<gear>.step`` per gear in ``folder``, made from its cut outline; none without the extra."""
    return write_part_solids(folder, gears=gear_drawings(toothed, problem.direction, problem.title,
                                                         cut_outlines(toothed)),
                             face_width=problem.solid_sizes.face_width(toothed.module), module=toothed.module)

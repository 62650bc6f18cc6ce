"""The reverse train's gears for the workshop, drawn as the five-bar's are (``fivebar.drawings``).

- ``<gear>.dxf`` and ``<gear>.svg`` per gear (``drawing.gear_sheet``): the cut tooth outline, the pitch curve, the
  keyed bore and the assembly mark towards the mate at carrier turn 0, the title block.
- ``drawings.pdf``: the sheets a page each (``drawing.pdf``); ``parts.csv``: a row per gear
  (``drawing.parts_list``).
- ``pitch_curve_<gear>.csv`` per gear: polar angle, radius, x, y in the gear's own frame.

Gears are named and placed as ``fivebar.gears_on_carrier`` places them for a carrier turning clockwise; a
carrier turning counterclockwise mirrors every part (y -> -y). The reverse problem carries no loads, so each
shaft takes the largest standard diameter within ``shafts.sizing.GEAR_SIZE_FRACTION`` of the smallest root radius
of the gears keyed to it (``shafts.sizing.diameter_for_gear``), with its DIN 6885-1 key; each keyway is checked
against its gear's root (``shafts.sizing.rim_failures``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from transplanter.drawing.gear_sheet import GearDrawing, write_gear_sheet
from transplanter.drawing.parts_list import write_parts_list
from transplanter.drawing.pdf import write_pdf
from transplanter.fivebar.drawings import toothed_gear_drawings, write_pitch_curves
from transplanter.fivebar.gears_on_carrier import gears_on_carrier, tooth_outlines
from transplanter.fivebar.shafts import SHAFT_OF_GEAR
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.sizing import diameter_for_gear, rim_failures
from transplanter.trains.toothed_train import ToothedTrain


def root_radii(toothed: ToothedTrain) -> dict[str, float]:
    """Each gear's smallest outline radius (mm), by the names of ``gears_on_carrier``."""
    return {gear.name.replace(" ", "_"): float(np.linalg.norm(gear.outline, axis=1).min()) for gear in toothed.gears}


def gear_bores(toothed: ToothedTrain) -> dict[str, KeyedBore]:
    """Each gear's keyed bore: its shaft sized by the smallest root on it, the keyway on the gear's mark."""
    roots = root_radii(toothed)
    diameters = {shaft: diameter_for_gear(min(roots[g] for g, s in SHAFT_OF_GEAR.items() if s == shaft))
                 for shaft in set(SHAFT_OF_GEAR.values())}
    return {gear.name: KeyedBore.for_shaft(diameters[SHAFT_OF_GEAR[gear.name]], gear.contact_direction,
                                           f"shafts.{SHAFT_OF_GEAR[gear.name]}_mm")
            for gear in gears_on_carrier(toothed.train, toothed.carrier_length)}


def bore_failures(toothed: ToothedTrain) -> list[str]:
    """Each gear whose keyway leaves too thin a rim under the teeth, with the numbers."""
    roots = root_radii(toothed)
    return [text for name, bore in gear_bores(toothed).items()
            for text in rim_failures(f"{name.replace('_', ' ')} bore", roots[name], bore, toothed.module)]


def gear_drawings(toothed: ToothedTrain, direction: int, title: str,
                  outlines: dict[str, np.ndarray] | None = None) -> list[GearDrawing]:
    """The four gears to make, mirrored for a carrier turning counterclockwise (``direction`` +1), with the drawn
    tooth outlines or the given ``outlines`` by name."""
    outlines = tooth_outlines(toothed) if outlines is None else outlines
    return toothed_gear_drawings(toothed, outlines, gear_bores(toothed), title, direction == 1)


def write_gear_files(toothed: ToothedTrain, direction: int, title: str, folder: Path) -> list[Path]:
    """The gear sheets, their PDF, parts.csv and the pitch-curve tables of the module docstring in ``folder``; the
    files written."""
    drawings = gear_drawings(toothed, direction, title)
    files = [write_gear_sheet(gear, folder) for gear in drawings]
    pages = [(f"{gear.name}.dxf", sheet.document) for gear, (sheet, _) in zip(drawings, files, strict=True)]
    return [*(path for _, written in files for path in written), write_pdf(pages, folder / "drawings.pdf"),
            write_parts_list((), drawings, folder / "parts.csv"),
            *write_pitch_curves(toothed.train, toothed.carrier_length, folder, direction == 1)]

"""``parts.csv``: one row per part to make, with what a workshop orders and checks it by."""
from __future__ import annotations

import csv
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from transplanter.drawing.gear_sheet import GearDrawing
from transplanter.drawing.plate_sheet import PlatePart

COLUMNS = ("part", "quantity", "key_dimensions_mm", "teeth", "module_mm", "material")


def plate_dimensions(part: PlatePart) -> str:
    """Centre distances and hole diameters, e.g. ``O-A 120.000; O 20 hole``."""
    centers = part.centers
    distances = [f"{a}-{b} {np.linalg.norm(centers[a] - centers[b]):.3f}" for a, b in part.dimensioned]
    holes = [f"{hole.label} {hole.diameter:g} hole" for hole in part.holes if hole.diameter]
    return "; ".join(distances + holes)


def gear_dimensions(gear: GearDrawing) -> str:
    """Bore, key and keyway depth d + t2, root radius."""
    bore, key = gear.bore, gear.bore.key
    return (f"bore {bore.diameter:g}; key {key.width:g} x {key.height:g} (DIN 6885-1); "
            f"d + t2 {bore.diameter + key.hub_depth:g}; root radius {gear.root_radius:.3f}")


def write_parts_list(plates: Sequence[PlatePart], gears: Sequence[GearDrawing], path: Path) -> Path:
    """One row per plate, then per gear (columns ``COLUMNS``; material left blank)."""
    with path.open("w", newline="") as stream:
        writer = csv.writer(stream, lineterminator="\n")
        writer.writerow(COLUMNS)
        for part in plates:
            writer.writerow([part.name, part.title.quantity, plate_dimensions(part), "", "", part.title.material])
        for gear in gears:
            title = gear.title
            writer.writerow([gear.name, title.quantity, gear_dimensions(gear), title.teeth or "",
                             "" if title.module is None else f"{title.module:g}", title.material])
    return path

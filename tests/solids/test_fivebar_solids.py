"""The five-bar's STEP solids: each link plate its outline less its holes (read back from its file), each gear its
drawn tooth outline less its keyed bore, extruded to the problem's thickness and face width.

A gear's STEP of the main job holds about 2,900 side faces and takes OpenCASCADE about a minute to read back, so
the gears are checked as the solids the writer exports (those ``solids.step.gear_solid`` made for it); reading a
gear's STEP back is tested on smaller gears through the same writer (test_step.py, test_command_solids.py,
test_reverse_solids.py)."""
from dataclasses import replace

import numpy as np
import shapely

from tests.solids.step_checks import check_solid, keyed_hole_area, read_step
from transplanter.fivebar.drawings import gear_drawings, parts
from transplanter.fivebar.gears_on_carrier import tooth_outlines
from transplanter.fivebar.solid_files import write_solids
from transplanter.solids import part_files
from transplanter.solids.sizes import SolidSizes
from transplanter.solids.step import gear_solid

ISO_10303 = b"ISO-10303-21;"


def test_every_plate_and_gear_is_its_drawing_extruded(example_result, tmp_path, monkeypatch):
    sizes = SolidSizes(face_width_mm=14.0, thickness_mm=5.0)
    result = replace(example_result, problem=replace(example_result.problem, solid_sizes=sizes))
    exported = {}

    def kept(gear, face_width):
        exported[gear.name] = gear_solid(gear, face_width)
        return exported[gear.name]
    monkeypatch.setattr(part_files, "gear_solid", kept)
    written = write_solids(result, tmp_path)
    plates, gears = parts(result), gear_drawings(result, tooth_outlines(result.toothed))
    assert sorted(path.name for path in written) == sorted(f"{part.name}.step" for part in [*plates, *gears])
    for part in plates:
        holes = [hole for hole in part.holes if hole.diameter]
        area = shapely.Polygon(part.outline()).area - sum(np.pi * (hole.diameter / 2) ** 2 for hole in holes)
        check_solid(read_step(tmp_path / f"{part.name}.step"), part.outline(), area, 5.0, len(holes))
    for gear in gears:
        assert (tmp_path / f"{gear.name}.step").read_bytes().startswith(ISO_10303)
        area = shapely.Polygon(gear.outline).area - keyed_hole_area(gear.bore)
        check_solid(exported[gear.name], gear.outline, area, 14.0, 1)

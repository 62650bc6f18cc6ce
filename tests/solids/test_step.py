"""STEP solids read back: volume = outline area x width within 0.1 %, bounding box, hole count. Skipped only
without the optional extra transplanter[cad] (build123d)."""
from pathlib import Path

import numpy as np
import shapely

from tests.solids.step_checks import check_solid, keyed_hole_area, read_back
from transplanter import gears
from transplanter.drawing.gear_sheet import GearDrawing
from transplanter.drawing.plate_sheet import Hole, PlatePart
from transplanter.drawing.sheet import TitleBlock
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.solids.step import FIXED_TIME, GEAR_WITHIN_MODULES, gear_solid, plate_solid, write_step

ROOT = Path(__file__).resolve().parents[2]


def test_plate_solid_has_the_outline_less_its_holes_times_its_thickness(tmp_path):
    holes = (Hole("O", np.zeros(2), 12.0), Hole("A", np.array([90.0, 0.0]), 10.0),
             Hole("S", np.array([30.0, 45.0]), 8.0))
    part = PlatePart("carrier", holes, (("O", "A"),), TitleBlock("carrier", 1, "t"))
    thickness = 6.0
    solid = read_back(plate_solid(part, thickness), tmp_path / "carrier.step")
    outline = part.outline()
    area = shapely.Polygon(outline).area - sum(np.pi * (hole.diameter / 2) ** 2 for hole in holes)
    check_solid(solid, outline, area, thickness, 3)


def test_gear_solid_has_the_tooth_outline_less_its_keyed_bore_times_its_face_width(tmp_path):
    pair = gears.synthesize(gears.load_problem(ROOT / "examples/gear_ellipse.toml"))
    module = pair.problem.module
    outline = pair.teeth.outlines[0]
    bore = KeyedBore.for_shaft(20.0, 0.3)
    gear = GearDrawing("driver", outline, outline, bore, TitleBlock("driver", 1, "t"))
    width = 10 * module
    solid = read_back(gear_solid(gear, width, module), tmp_path / "driver.step")
    check_solid(solid, outline, shapely.Polygon(outline).area - keyed_hole_area(bore), width, 1,
                within=1.1 * GEAR_WITHIN_MODULES * module)


def test_the_same_part_gives_the_same_step_bytes(tmp_path):
    part = PlatePart("rod", (Hole("A", np.zeros(2), 10.0), Hole("F", np.array([80.0, 0.0]), 8.0)), (("A", "F"),),
                     TitleBlock("rod", 1, "t"))
    first = write_step(plate_solid(part, 5.0), tmp_path / "first.step")
    second = write_step(plate_solid(part, 5.0), tmp_path / "second.step")
    assert first.read_bytes() == second.read_bytes()
    assert f"'{FIXED_TIME}'" in first.read_text().split("ENDSEC;")[0]

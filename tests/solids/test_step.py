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
from transplanter.geometry.outline_thinning import thinned
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.solids.step import FIXED_TIME, gear_solid, plate_solid, valid_outline, write_step

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
    outline = thinned(pair.teeth.outlines[0], 1e-3 * module)
    bore = KeyedBore.for_shaft(20.0, 0.3)
    gear = GearDrawing("driver", outline, outline, bore, TitleBlock("driver", 1, "t"))
    width = 10 * module
    solid = read_back(gear_solid(gear, width), tmp_path / "driver.step")
    check_solid(solid, outline, shapely.Polygon(outline).area - keyed_hole_area(bore), width, 1)


def test_the_same_part_gives_the_same_step_bytes(tmp_path):
    part = PlatePart("rod", (Hole("A", np.zeros(2), 10.0), Hole("F", np.array([80.0, 0.0]), 8.0)), (("A", "F"),),
                     TitleBlock("rod", 1, "t"))
    first = write_step(plate_solid(part, 5.0), tmp_path / "first.step")
    second = write_step(plate_solid(part, 5.0), tmp_path / "second.step")
    assert first.read_bytes() == second.read_bytes()
    assert f"'{FIXED_TIME}'" in first.read_text().split("ENDSEC;")[0]


def test_an_outline_crossing_itself_gives_the_largest_region_it_encloses(tmp_path):
    """A 40 x 30 mm outline that crosses itself at its seam, a loop 0.001 mm across (as a cut tooth outline can): the
    solid is valid, the rectangle less the keyed bore times the width."""
    outline = np.array([[-20.0, -15.0], [20.0, -15.0], [20.0, 15.0], [-20.0, 15.0], [-19.999, -15.001]])
    assert not shapely.Polygon(outline).is_valid
    cleaned = valid_outline(outline)
    assert shapely.Polygon(cleaned).is_valid
    assert np.allclose(cleaned.min(axis=0), [-20.0, -15.0]) and np.allclose(cleaned.max(axis=0), [20.0, 15.0])
    bore = KeyedBore.for_shaft(10.0, 0.0)
    gear = GearDrawing("block", outline, outline, bore, TitleBlock("block", 1, "t"))
    solid = gear_solid(gear, 4.0)
    assert solid.is_valid
    check_solid(read_back(solid, tmp_path / "block.step"), cleaned, 40.0 * 30.0 - keyed_hole_area(bore), 4.0, 1)

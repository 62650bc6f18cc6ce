"""STEP solids read back: volume = outline area x width within 0.1 %, bounding box, hole count. Skipped only
without the optional extra transplanter[cad] (build123d)."""
from pathlib import Path

import numpy as np
import pytest
import shapely

from transplanter import gears
from transplanter.drawing.gear_sheet import GearDrawing
from transplanter.drawing.plate_sheet import Hole, PlatePart
from transplanter.drawing.sheet import TitleBlock
from transplanter.geometry.outline_thinning import thinned
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.solids.step import FIXED_TIME, gear_solid, plate_solid, write_step

bd = pytest.importorskip("build123d")

ROOT = Path(__file__).resolve().parents[2]


def _read_back(solid, path: Path):
    write_step(solid, path)
    return bd.import_step(str(path))


def _check_solid(solid, outline: np.ndarray, area: float, height: float, holes: int):
    """Volume = area x height within 0.1 %, the outline's bounding box and ``height``, ``holes`` through the top."""
    assert solid.volume == pytest.approx(area * height, rel=1e-3)
    box = solid.bounding_box()
    assert np.allclose([box.min.X, box.min.Y, box.max.X, box.max.Y], [*outline.min(axis=0), *outline.max(axis=0)],
                       atol=1e-6)
    assert abs(box.size.Z - height) < 1e-9
    assert len(solid.faces().sort_by(bd.Axis.Z)[-1].inner_wires()) == holes


def _keyed_hole_area(bore: KeyedBore) -> float:
    """The disk, less its segment beyond the keyway's chord, plus the keyway's rectangle from that chord out."""
    r, alpha = bore.radius, bore.half_angle
    return (np.pi * r**2 - r**2 * (alpha - np.sin(alpha) * np.cos(alpha))
            + bore.key.width * (bore.reach - r * np.cos(alpha)))


def test_plate_solid_has_the_outline_less_its_holes_times_its_thickness(tmp_path):
    holes = (Hole("O", np.zeros(2), 12.0), Hole("A", np.array([90.0, 0.0]), 10.0),
             Hole("S", np.array([30.0, 45.0]), 8.0))
    part = PlatePart("carrier", holes, (("O", "A"),), TitleBlock("carrier", 1, "t"))
    thickness = 6.0
    solid = _read_back(plate_solid(part, thickness), tmp_path / "carrier.step")
    outline = part.outline()
    area = shapely.Polygon(outline).area - sum(np.pi * (hole.diameter / 2) ** 2 for hole in holes)
    _check_solid(solid, outline, area, thickness, 3)


def test_gear_solid_has_the_tooth_outline_less_its_keyed_bore_times_its_face_width(tmp_path):
    pair = gears.synthesize(gears.load_problem(ROOT / "examples/gear_ellipse.toml"))
    module = pair.problem.module
    outline = thinned(pair.teeth.outlines[0], 1e-3 * module)
    bore = KeyedBore.for_shaft(20.0, 0.3)
    gear = GearDrawing("driver", outline, outline, bore, TitleBlock("driver", 1, "t"))
    width = 10 * module
    solid = _read_back(gear_solid(gear, width), tmp_path / "driver.step")
    _check_solid(solid, outline, shapely.Polygon(outline).area - _keyed_hole_area(bore), width, 1)


def test_the_same_part_gives_the_same_step_bytes(tmp_path):
    part = PlatePart("rod", (Hole("A", np.zeros(2), 10.0), Hole("F", np.array([80.0, 0.0]), 8.0)), (("A", "F"),),
                     TitleBlock("rod", 1, "t"))
    first = write_step(plate_solid(part, 5.0), tmp_path / "first.step")
    second = write_step(plate_solid(part, 5.0), tmp_path / "second.step")
    assert first.read_bytes() == second.read_bytes()
    assert f"'{FIXED_TIME}'" in first.read_text().split("ENDSEC;")[0]

"""The reverse train's STEP solids read back: each gear its drawn tooth outline less its keyed bore, extruded to
the problem's ``train.face_width_mm``."""
from dataclasses import replace

import shapely

from tests.solids.step_checks import check_solid, keyed_hole_area, read_step
from transplanter.reverse.gear_files import gear_drawings
from transplanter.reverse.solid_files import write_solids
from transplanter.solids.sizes import SolidSizes
from transplanter.solids.step import gear_solid


def test_every_reverse_gear_is_its_drawing_extruded(rice_result, tmp_path):
    problem = replace(rice_result.problem, solid_sizes=SolidSizes(face_width_mm=11.0))
    result = replace(rice_result, problem=problem)
    written = write_solids(result.toothed, result.problem, tmp_path)
    drawings = gear_drawings(result.toothed, problem.direction, problem.title)
    assert [path.name for path in written] == [f"{gear.name}.step" for gear in drawings]
    assert len(drawings) == 4
    for gear in drawings:
        assert gear_solid(gear, 11.0).is_valid
        area = shapely.Polygon(gear.outline).area - keyed_hole_area(gear.bore)
        check_solid(read_step(tmp_path / f"{gear.name}.step"), gear.outline, area, 11.0, 1)
    assert result.to_json()["solids"] == "STEP solids: gears 11 mm wide"

"""The STEP solids the gear command writes, read back: each cut gear is its drawing's tooth outline less its keyed
bore, extruded to the problem's face width (its outline thinned within a thousandth of the module)."""
import dataclasses
from pathlib import Path

import shapely

from tests.solids.step_checks import bd, check_solid, keyed_hole_area
from transplanter import gears
from transplanter.gears.drawings import gear_drawings
from transplanter.geometry.outline_thinning import DRAWN_WITHIN_MODULES, thinned
from transplanter.solids.sizes import SolidSizes

ROOT = Path(__file__).resolve().parents[2]


def test_the_gear_commands_solids_are_its_drawings_extruded(tmp_path):
    problem = gears.load_problem(ROOT / "examples/gear_ellipse.toml")
    width = 13.0
    result = gears.synthesize(dataclasses.replace(problem, solid_sizes=SolidSizes(face_width_mm=width)))
    written = result.write_files(tmp_path)
    for gear in gear_drawings(result):
        path = tmp_path / f"{gear.name}.step"
        assert path in written
        # the volume against the drawn outline, the box against the one the solid was made from
        area = shapely.Polygon(gear.outline).area - keyed_hole_area(gear.bore)
        made_from = thinned(gear.outline, DRAWN_WITHIN_MODULES * problem.module)
        check_solid(bd.import_step(str(path)), made_from, area, width, 1)

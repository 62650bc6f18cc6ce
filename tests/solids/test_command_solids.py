"""The STEP solids the gear and parallelogram commands write, read back: each cut gear is its drawing's tooth
outline less its keyed bore, extruded to the problem's face width (its outline thinned within a thousandth of the
module)."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import shapely

from tests.solids.step_checks import check_solid, keyed_hole_area, read_step
from transplanter import gears
from transplanter.cli import main
from transplanter.gears.drawings import gear_drawings
from transplanter.geometry.outline_thinning import DRAWN_WITHIN_MODULES, thinned
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.sizing import diameter_for_gear
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
        check_solid(read_step(path), made_from, area, width, 1)
    assert result.to_json()["solids"] == f"STEP solids: gears {width:g} mm wide"


def test_no_step_writes_no_solid(tmp_path):
    out = tmp_path / "out"
    assert main(["gear", str(ROOT / "examples/gear_ellipse.toml"), "--quiet", "--no-step", "--out", str(out)]) == 0
    assert "solid" not in json.loads((out / "report.json").read_text())["files"]
    assert not list(out.glob("*.step"))


def test_the_onion_transplanters_gears_take_its_own_face_width(tmp_path):
    """A small search through the parallelogram command with [gear] face_width_mm: its cut pair's solids that
    wide, listed in report.json (no tolerance analysis: nothing here reads it)."""
    problem, out = tmp_path / "small.toml", tmp_path / "out"
    problem.write_text((ROOT / "examples/onion_transplanter.toml").read_text()
                       .replace("population = 100", "population = 16").replace("generations = 100", "generations = 6")
                       .replace("[gear]\n", "[gear]\nface_width_mm = 18.0\n"))
    assert main(["parallelogram", str(problem), "--no-animation", "--no-tolerance", "--quiet", "--out", str(out)]) == 0
    report = json.loads((out / "report.json").read_text())
    assert report["files"]["solid"] == ["driven.step", "driver.step"]
    assert report["solids"] == "STEP solids: gears 18 mm wide"
    for name in ("driver", "driven"):
        outline = np.loadtxt(out / f"{name}_teeth.csv", delimiter=",", skiprows=1)
        # the bore by the documented rule: the largest standard diameter within 0.8 of the root radius
        bore = KeyedBore.for_shaft(diameter_for_gear(float(np.linalg.norm(outline, axis=1).min())))
        area = shapely.Polygon(outline).area - keyed_hole_area(bore)
        check_solid(read_step(out / f"{name}.step"), thinned(outline, DRAWN_WITHIN_MODULES * 2.0), area,
                    18.0, 1)

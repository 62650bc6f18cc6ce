"""The STEP solids the gear and parallelogram commands write, read back: each cut gear is its drawing's tooth
outline (as smooth curves within ``solids.step.GEAR_WITHIN_MODULES`` of the module) less its keyed bore, extruded
to the problem's face width."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import shapely

from tests.solids.step_checks import check_solid, keyed_hole_area, read_step
from transplanter import gears
from transplanter.cli import main
from transplanter.gears.drawings import gear_drawings
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.sizing import diameter_for_gear
from transplanter.solids.sizes import SolidSizes
from transplanter.solids.step import GEAR_WITHIN_MODULES

ROOT = Path(__file__).resolve().parents[2]


def test_the_gear_commands_solids_are_its_drawings_extruded(tmp_path):
    problem = gears.load_problem(ROOT / "examples/gear_ellipse.toml")
    width = 13.0
    result = gears.synthesize(dataclasses.replace(problem, solid_sizes=SolidSizes(face_width_mm=width)))
    written = result.write_files(tmp_path)
    for gear in gear_drawings(result):
        path = tmp_path / f"{gear.name}.step"
        assert path in written
        area = shapely.Polygon(gear.outline).area - keyed_hole_area(gear.bore)
        check_solid(read_step(path), gear.outline, area, width, 1, within=1.1 * GEAR_WITHIN_MODULES * problem.module)
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
        # the teeth table's 1e-9 mm digits are far inside the solid's bound
        check_solid(read_step(out / f"{name}.step"), outline, area, 18.0, 1, within=1.1 * GEAR_WITHIN_MODULES * 2.0)

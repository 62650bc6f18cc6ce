"""The cam disc's STEP solid read back (the drawn profile less its bore, extruded to ``cam.thickness_mm``), the
thickness's default rule, its bad values in one line, and its round trip through design.toml."""
import dataclasses
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest
import shapely

from tests.solids.step_checks import check_solid, read_step
from transplanter import cam
from transplanter.cam.drawings import bore_radius
from transplanter.cam.solid_files import disc_outline, write_solids
from transplanter.errors import ProblemError
from transplanter.solids.sizes import PLATE_THICKNESS_PIN_DIAMETERS, SolidSizes
from transplanter.solids.step import DISC_WITHIN_EXTENT

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "cam_flat_faced.toml"


def _with_thickness(thickness):
    data = tomllib.loads(EXAMPLE.read_text())
    data["cam"]["thickness_mm"] = thickness
    return cam.parse_problem(data, "x")


def test_the_cam_disc_is_its_profile_less_its_bore_extruded(tmp_path):
    result = cam.synthesize(_with_thickness(9.0))
    assert [path.name for path in write_solids(result, tmp_path)] == ["cam.step"]
    profile, radius = result.geometry.profile, bore_radius(result)
    area = shapely.Polygon(profile).area - np.pi * radius**2
    outline = disc_outline(result)
    within = 1.1 * DISC_WITHIN_EXTENT * float(np.ptp(outline, axis=0).max())
    check_solid(read_step(tmp_path / "cam.step"), outline, area, 9.0, 1, within=within)
    assert result.to_json()["solids"] == "STEP solids: cam disc 9 mm thick"


def test_the_default_thickness_is_the_plate_rule_on_the_bore():
    result = cam.synthesize(cam.load_problem(EXAMPLE))
    assert result.problem.solid_sizes == SolidSizes()
    thickness = PLATE_THICKNESS_PIN_DIAMETERS * 2 * bore_radius(result)
    assert result.to_json()["solids"].endswith(f"cam disc {thickness:g} mm thick")


@pytest.mark.parametrize("value", [0.0, -3.0, "thick"])
def test_a_bad_thickness_names_the_field(value):
    with pytest.raises(ProblemError, match=rf"cam\.thickness_mm = {re.escape(repr(value))}: expected a"):
        _with_thickness(value)


@pytest.mark.parametrize("given", [None, 7.5])
def test_the_thickness_is_written_to_the_design_and_read_back(tmp_path, given):
    problem = dataclasses.replace(cam.load_problem(EXAMPLE), solid_sizes=SolidSizes(thickness_mm=given))
    result = cam.synthesize(problem)
    result.write_files(tmp_path, solids=False)
    written = tomllib.loads((tmp_path / "design.toml").read_text())["cam"]["thickness_mm"]
    assert written == (given or PLATE_THICKNESS_PIN_DIAMETERS * 2 * bore_radius(result))
    again = cam.evaluate_design(cam.load_problem(EXAMPLE), cam.load_design(tmp_path / "design.toml"))
    assert again.problem.solid_sizes == SolidSizes(thickness_mm=written)
    assert again.to_json()["solids"] == result.to_json()["solids"]

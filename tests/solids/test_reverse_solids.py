"""The reverse train's STEP solids read back: each gear its cut tooth outline as smooth curves less its keyed bore,
extruded to the problem's ``train.face_width_mm``, its edges measured against that outline and the drawn one."""
from dataclasses import replace

import shapely

from tests.solids.step_checks import check_solid, distance_to_lines, edge_samples, keyed_hole_area, read_step
from transplanter.fivebar.gears_on_carrier import cut_outlines
from transplanter.reverse.gear_files import gear_drawings
from transplanter.reverse.solid_files import write_solids
from transplanter.solids.sizes import SolidSizes
from transplanter.solids.step import GEAR_WITHIN_MODULES

#: The edges are sampled every this many modules; between samples a chord is as far from the curve as its sagitta
#: (below 1e-5 module on the fillets), so the distances hold the bound plus a tenth of it.
SAMPLE_MODULES = 2e-3


def test_every_reverse_gear_is_its_cut_outline_extruded(rice_result, tmp_path):
    problem = replace(rice_result.problem, solid_sizes=SolidSizes(face_width_mm=11.0))
    result = replace(rice_result, problem=problem)
    module = result.toothed.module
    written = write_solids(result.toothed, result.problem, tmp_path)
    drawings = gear_drawings(result.toothed, problem.direction, problem.title)
    cut = gear_drawings(result.toothed, problem.direction, problem.title, cut_outlines(result.toothed))
    assert [path.name for path in written] == [f"{gear.name}.step" for gear in drawings]
    assert len(drawings) == 4
    within = GEAR_WITHIN_MODULES * module
    for gear, cut_gear in zip(drawings, cut, strict=True):
        solid = read_step(tmp_path / f"{gear.name}.step")
        assert solid.is_valid
        area = shapely.Polygon(gear.outline).area - keyed_hole_area(gear.bore)
        # the box against the cut outline the solid follows within ``within``
        check_solid(solid, cut_gear.outline, area, 11.0, 1, within=1.1 * within)
        # every point of the cut outline within the bound of the solid's edge (its outline is sparse here, a point
        # every 0.04 module: between points the edge follows the curve, not the chord; test_fivebar_solids measures
        # the edge against the drawn polyline of a dense outline)
        edges = edge_samples(solid, SAMPLE_MODULES * module)
        assert distance_to_lines(cut_gear.outline, edges, SAMPLE_MODULES * module).max() <= 1.1 * within
    assert result.to_json()["solids"] == "STEP solids: gears 11 mm wide"

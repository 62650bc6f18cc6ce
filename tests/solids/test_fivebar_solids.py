"""The five-bar's STEP solids read back: each link plate its outline less its holes, each gear its cut tooth outline
as smooth curves less its keyed bore, extruded to the problem's thickness and face width; a gear's edges measured
against its cut outline and its drawn polyline."""
from dataclasses import replace

import numpy as np
import shapely

from tests.solids.step_checks import check_solid, distance_to_lines, edge_samples, keyed_hole_area, read_step
from transplanter.fivebar.drawings import gear_drawings, parts
from transplanter.fivebar.gears_on_carrier import cut_outlines, tooth_outlines
from transplanter.fivebar.solid_files import write_solids
from transplanter.geometry.outline_thinning import DRAWN_WITHIN_MODULES
from transplanter.solids.sizes import SolidSizes
from transplanter.solids.step import GEAR_WITHIN_MODULES

#: The edges are sampled every this many modules; between samples a chord is as far from the curve as its sagitta
#: (below 1e-5 module on the fillets), so the distances hold the bounds plus a tenth of the solid's.
SAMPLE_MODULES = 2e-3


def test_every_plate_and_gear_is_its_drawing_extruded(example_result, tmp_path):
    sizes = SolidSizes(face_width_mm=14.0, thickness_mm=5.0)
    result = replace(example_result, problem=replace(example_result.problem, solid_sizes=sizes))
    written = write_solids(result, tmp_path)
    plates, gears = parts(result), gear_drawings(result, tooth_outlines(result.toothed))
    cut = cut_outlines(result.toothed)
    assert sorted(path.name for path in written) == sorted(f"{part.name}.step" for part in [*plates, *gears])
    for part in plates:
        holes = [hole for hole in part.holes if hole.diameter]
        area = shapely.Polygon(part.outline()).area - sum(np.pi * (hole.diameter / 2) ** 2 for hole in holes)
        check_solid(read_step(tmp_path / f"{part.name}.step"), part.outline(), area, 5.0, len(holes))
    module = result.toothed.module
    within, spacing = GEAR_WITHIN_MODULES * module, SAMPLE_MODULES * module
    for gear in gears:
        solid = read_step(tmp_path / f"{gear.name}.step")
        area = shapely.Polygon(gear.outline).area - keyed_hole_area(gear.bore)
        check_solid(solid, cut[gear.name], area, 14.0, 1, within=1.1 * within)
        edges = edge_samples(solid, spacing)
        # every point of the cut outline (a point every 0.002 module) within the bound of the edge, every sample of
        # the edge within the drawing's own chord tolerance plus that bound of the drawn polyline
        assert distance_to_lines(cut[gear.name], edges, spacing).max() <= 1.1 * within
        drawn = np.vstack([gear.outline, gear.outline[:1]])
        drawing_tolerance = DRAWN_WITHIN_MODULES * module
        assert distance_to_lines(np.vstack(edges), [drawn], spacing).max() <= drawing_tolerance + 1.1 * within

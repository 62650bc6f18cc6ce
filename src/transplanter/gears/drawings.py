"""Drawings of gears in millimetres: CSV tables, SVG and DXF outlines ready for CAD or wire cutting.

Each gear is drawn in its own frame with its center at the origin; at phi1 = 0 the contact
point is on +x of the driver and on -x of the driven gear. The sheets follow ``drawing.sheet``.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from transplanter.api_arguments import require_result
from transplanter.drawing.gear_sheet import GearDrawing, write_gear_sheets
from transplanter.drawing.sheet import TitleBlock
from transplanter.gears.result import GearResult
from transplanter.gears.teeth import driven_table, driver_table
from transplanter.output_folder import writable_folder
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.sizing import diameter_for_gear, rim_failures

NAMES = ("driver", "driven")


def outlines(result: GearResult) -> dict[str, np.ndarray]:
    """Closed outline per gear: the tooth profile when generated, else the pitch curve."""
    if result.teeth is not None:
        return dict(zip(NAMES, result.teeth.outlines, strict=True))
    return {name: points[:-1] for name, points in zip(NAMES, _pitch_curves(result), strict=True)}


def _pitch_curves(result: GearResult):
    return driver_table(result.design).points, driven_table(result.design).points


def write_csv(result: GearResult, folder: Path) -> list[Path]:
    d = result.design
    columns = {
        "phi1_deg": np.degrees(d.phi1), "phi2_deg": np.degrees(d.phi2),
        "driver_radius_mm": d.radius[0], "driven_radius_mm": d.radius[1],
        "driver_x_mm": d.points[0][:, 0], "driver_y_mm": d.points[0][:, 1],
        "driven_x_mm": d.points[1][:, 0], "driven_y_mm": d.points[1][:, 1],
        "ratio_i12": d.ratio, "driven_speed_rad_s": d.driven_speed, "driven_acceleration_rad_s2": d.driven_acceleration,
        "driver_curvature_radius_mm": d.curvature_radius[0], "driven_curvature_radius_mm": d.curvature_radius[1],
    }
    written = [folder / "pitch_curves.csv"]
    np.savetxt(written[0], np.column_stack(list(columns.values())), delimiter=",", header=",".join(columns),
               comments="", fmt="%.12g")
    if result.teeth is not None:
        for name, outline in outlines(result).items():
            path = folder / f"{name}_teeth.csv"
            np.savetxt(path, outline, delimiter=",", header="x_mm,y_mm", comments="", fmt="%.9f")
            written.append(path)
    return written


def gear_drawings(result: GearResult) -> list[GearDrawing]:
    """Both gears to make: the bore by ``shafts.sizing.diameter_for_gear`` (a gear pair alone has no loads), its
    keyway and mark towards the contact point at phi1 = 0 (+x on the driver, -x on the driven gear)."""
    problem, counts = result.problem, result.tooth_counts
    drawings = []
    for index, ((name, outline), pitch_curve) in enumerate(zip(outlines(result).items(), _pitch_curves(result),
                                                               strict=True)):
        root = float(np.linalg.norm(outline, axis=1).min())
        title = TitleBlock(name, 1, problem.title, module=problem.module,
                           teeth=None if counts is None else counts.counts[index],
                           pressure_angle_deg=None if counts is None else float(np.degrees(problem.pressure_angle)),
                           center_distance_mm=result.design.center_distance)
        bore = KeyedBore.for_shaft(diameter_for_gear(root), np.pi * index)
        drawings.append(GearDrawing(name, outline, pitch_curve, bore, title))
    return drawings


def bore_failures(result: GearResult) -> list[str]:
    """Each cut gear whose keyed bore leaves too thin a rim under its teeth (``shafts.sizing.rim_failures``), with
    the numbers; none before teeth are cut."""
    module = result.problem.module
    if result.teeth is None or module is None:
        return []
    return [text for gear in gear_drawings(result)
            for text in rim_failures(f"{gear.name} bore", gear.root_radius, gear.bore, module)]


def write_drawings(result: GearResult, folder: str | Path) -> list[Path]:
    """Write the pitch curves and tooth outlines of both gears into ``folder`` (made if missing).

    Parameters
    ----------
    result : GearResult
        A designed gear pair (``gears.synthesize``).
    folder : str or Path
        Output folder.

    Returns
    -------
    list of Path
        The files written: CSV (pitch curves, outlines; mm), SVG and DXF per gear in the convention of
        ``drawing.sheet`` (outline, pitch curve, keyed bore, assembly mark, dimensions, title block).
    """
    require_result(result, GearResult, "gears")
    folder = writable_folder(folder)
    return write_csv(result, folder) + write_gear_sheets(gear_drawings(result), folder)

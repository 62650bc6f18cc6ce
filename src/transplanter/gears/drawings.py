"""Drawings of a gear pair in millimetres: CSV tables, SVG and DXF outlines ready for CAD or wire cutting.

Each gear is drawn in its own frame with its center at the origin; at phi1 = 0 the contact
point is on +x of the driver and on -x of the driven gear.
"""
from __future__ import annotations

from pathlib import Path

import ezdxf
import numpy as np

from transplanter.gears.result import GearResult
from transplanter.gears.teeth import driven_table, driver_table

NAMES = ("driver", "driven")


def outlines(result: GearResult) -> dict[str, np.ndarray]:
    """Closed outline per gear: the tooth profile when generated, else the pitch curve."""
    if result.teeth is not None:
        return dict(zip(NAMES, result.teeth.outlines))
    return {name: points[:-1] for name, points in zip(NAMES, _pitch_curves(result))}


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


def write_svg(outline: np.ndarray, path: Path):
    margin = 5.0
    low, high = outline.min(axis=0) - margin, outline.max(axis=0) + margin
    width, height = high - low
    # SVG's y axis points down: flip so the drawing matches the mathematical frame.
    points = " ".join(f"{x - low[0]:.6f},{high[1] - y:.6f}" for x, y in outline)
    cx, cy = -low[0], high[1]
    path.write_text(
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.3f}mm" height="{height:.3f}mm" '
        f'viewBox="0 0 {width:.6f} {height:.6f}">\n'
        f'  <polygon points="{points}" fill="none" stroke="black" stroke-width="0.1"/>\n'
        f'  <circle cx="{cx:.6f}" cy="{cy:.6f}" r="1" fill="none" stroke="red" stroke-width="0.1"/>\n'
        f'</svg>\n')


def write_dxf(outline: np.ndarray, path: Path):
    document = ezdxf.new("R2010", setup=False)
    document.units = ezdxf.units.MM
    space = document.modelspace()
    document.layers.add("OUTLINE")
    document.layers.add("CENTER")
    space.add_lwpolyline(outline.tolist(), close=True, dxfattribs={"layer": "OUTLINE"})
    space.add_circle((0.0, 0.0), 1.0, dxfattribs={"layer": "CENTER"})
    document.saveas(path)


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
        The files written: CSV (pitch curves, outlines; mm), SVG and DXF (mm, INSUNITS set) per gear.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written = write_csv(result, folder)
    for name, outline in outlines(result).items():
        for suffix, writer in ((".svg", write_svg), (".dxf", write_dxf)):
            path = folder / f"{name}{suffix}"
            writer(outline, path)
            written.append(path)
    return written

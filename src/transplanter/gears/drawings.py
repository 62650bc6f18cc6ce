"""Drawings of gears in millimetres: CSV tables, SVG and DXF outlines ready for CAD or wire cutting.

Each gear is drawn in its own frame with its center at the origin; at phi1 = 0 the contact
point is on +x of the driver and on -x of the driven gear. ``write_gear_drawings`` draws any
gear for manufacture: teeth, pitch curve, bore and the assembly mark, each on its own layer.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf.entities.lwpolyline import LWPolylinePoints

from transplanter.api_arguments import require_result
from transplanter.gears.result import GearResult
from transplanter.gears.teeth import driven_table, driver_table
from transplanter.output_folder import writable_folder

NAMES = ("driver", "driven")
#: Bore radius of ``default_bore_radius`` as a fraction of the gear's smallest outline radius (its root).
BORE_FRACTION = 0.4
#: The assembly mark runs from the bore out to this fraction of the smallest outline radius.
MARK_REACH = 0.9
LAYERS = {"teeth": "TEETH", "pitch": "PITCH", "bore": "BORE", "mark": "MARK"}


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


def write_svg(outline: np.ndarray, path: Path, *, pitch_curve: np.ndarray | None = None,
              bore_radius: float | None = None, mark: np.ndarray | None = None):
    """Outline (N, 2) mm as an SVG in mm; optionally the pitch curve (dashed), the bore circle (in place
    of the 1 mm centre circle) and the assembly mark (2, 2) mm."""
    margin = 5.0
    low, high = outline.min(axis=0) - margin, outline.max(axis=0) + margin
    width, height = high - low

    # SVG's y axis points down: flip so the drawing matches the mathematical frame.
    def svg_points(points):
        return " ".join(f"{x - low[0]:.6f},{high[1] - y:.6f}" for x, y in points)

    cx, cy = -low[0], high[1]
    extras = ""
    if pitch_curve is not None:
        extras += (f'  <polyline points="{svg_points(pitch_curve)}" fill="none" stroke="blue" stroke-width="0.1" '
                   f'stroke-dasharray="1,0.5"/>\n')
    if mark is not None:
        extras += f'  <polyline points="{svg_points(mark)}" fill="none" stroke="red" stroke-width="0.2"/>\n'
    path.write_text(
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.3f}mm" height="{height:.3f}mm" '
        f'viewBox="0 0 {width:.6f} {height:.6f}">\n'
        f'  <polygon points="{svg_points(outline)}" fill="none" stroke="black" stroke-width="0.1"/>\n'
        f'  <circle cx="{cx:.6f}" cy="{cy:.6f}" r="{1 if bore_radius is None else bore_radius:.6g}" fill="none" '
        f'stroke="red" stroke-width="0.1"/>\n'
        f'{extras}</svg>\n')


def _polyline(space, points: np.ndarray, layer: str, close: bool):
    """An LWPOLYLINE of ``points`` (N, 2) mm with its vertex array filled at once: ezdxf 1.4's
    ``add_lwpolyline`` appends point by point, each a copy of the array so far (16 s for the four outlines of a
    100-tooth composite pair, against 0.1 s this way)."""
    polyline = space.add_lwpolyline([], close=close, dxfattribs={"layer": layer})
    polyline.lwpoints = LWPolylinePoints(np.c_[points, np.zeros((len(points), 3))].tolist())


def write_dxf(outline: np.ndarray, path: Path, *, outline_layer: str = "OUTLINE", pitch_curve: np.ndarray | None = None,
              bore_radius: float | None = None, mark: np.ndarray | None = None):
    """Outline (N, 2) mm as a closed polyline on ``outline_layer`` (INSUNITS mm); optionally the pitch curve
    (layer PITCH), the bore circle (layer BORE, in place of the 1 mm circle on CENTER) and the assembly
    mark (2, 2) mm (layer MARK)."""
    document = ezdxf.new("R2010", setup=False)
    document.units = ezdxf.units.MM
    space = document.modelspace()
    document.layers.add(outline_layer)
    _polyline(space, outline, outline_layer, close=True)
    if bore_radius is None:
        document.layers.add("CENTER")
        space.add_circle((0.0, 0.0), 1.0, dxfattribs={"layer": "CENTER"})
    else:
        document.layers.add(LAYERS["bore"])
        space.add_circle((0.0, 0.0), bore_radius, dxfattribs={"layer": LAYERS["bore"]})
    if pitch_curve is not None:
        document.layers.add(LAYERS["pitch"])
        _polyline(space, np.asarray(pitch_curve), LAYERS["pitch"], close=False)
    if mark is not None:
        document.layers.add(LAYERS["mark"])
        start, end = np.asarray(mark).tolist()
        space.add_line(start, end, dxfattribs={"layer": LAYERS["mark"]})
    document.saveas(path)


@dataclass(frozen=True)
class GearDrawing:
    """One gear to manufacture, in its own frame (centre at the origin), millimetres.

    ``outline`` (N, 2): closed tooth outline; ``pitch_curve`` (M, 2); ``bore_radius``; ``mark_direction``
    (rad, counterclockwise from +x): towards the contact point at the assembly pose.
    """

    name: str
    outline: np.ndarray
    pitch_curve: np.ndarray
    bore_radius: float
    mark_direction: float

    @property
    def mark(self) -> np.ndarray:
        """The assembly mark (2, 2): from the bore towards the contact point, short of the root."""
        root = float(np.linalg.norm(self.outline, axis=1).min())
        unit = np.array([np.cos(self.mark_direction), np.sin(self.mark_direction)])
        return np.outer([self.bore_radius, max(MARK_REACH * root, self.bore_radius)], unit)


def default_bore_radius(outline: np.ndarray) -> float:
    """``BORE_FRACTION`` of the smallest distance from the centre to the outline (mm)."""
    return BORE_FRACTION * float(np.linalg.norm(outline, axis=1).min())


def write_gear_drawings(gears, folder: str | Path) -> list[Path]:
    """``<name>.dxf`` and ``<name>.svg`` per ``GearDrawing`` in ``folder`` (made if missing).

    Layers: TEETH (outline), PITCH (pitch curve), BORE (bore circle), MARK (assembly mark); INSUNITS mm.
    Returns the files written.
    """
    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    written = []
    for gear in gears:
        extras = {"pitch_curve": gear.pitch_curve, "bore_radius": gear.bore_radius, "mark": gear.mark}
        write_dxf(gear.outline, folder / f"{gear.name}.dxf", outline_layer=LAYERS["teeth"], **extras)
        write_svg(gear.outline, folder / f"{gear.name}.svg", **extras)
        written += [folder / f"{gear.name}.dxf", folder / f"{gear.name}.svg"]
    return written


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
        The files written: CSV (pitch curves, outlines; mm), SVG and DXF (mm, INSUNITS set) per gear, the DXF
        with the outline on layer OUTLINE and the pitch curve on layer PITCH (dashed in the SVG).
    """
    require_result(result, GearResult, "gears")
    folder = writable_folder(folder)
    written = write_csv(result, folder)
    for (name, outline), pitch_curve in zip(outlines(result).items(), _pitch_curves(result), strict=True):
        for suffix, writer in ((".svg", write_svg), (".dxf", write_dxf)):
            path = folder / f"{name}{suffix}"
            writer(outline, path, pitch_curve=pitch_curve)
            written.append(path)
    return written

"""Drawings of a cam in millimetres, in the cam's own frame (centre at the origin, cam angle 0):

- ``cam_profile.csv``: per cam angle, the follower's motion, the pitch curve and the profile, the
  pressure angle and both curvature radii.
- ``cam.dxf`` in the convention of ``drawing.sheet``: the profile (OUTLINE, closed), the pitch curve (PITCH,
  closed; none for a flat-faced follower), the base circle and centre lines (CENTERLINES), the bore (BORE) with
  its diameter (DIMENSIONS) and the title block.
- ``cam.svg``: the profile, the pitch curve dashed and the bore.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from transplanter.api_arguments import require_result
from transplanter.cam.result import CamResult
from transplanter.drawing.sheet import Sheet, TitleBlock
from transplanter.drawing.svg import write_svg
from transplanter.output_folder import writable_folder

#: The default bore radius as a fraction of the profile's smallest radius.
BORE_FRACTION = 0.4
#: Sides of the bore's polygon in the SVG.
BORE_SEGMENTS = 360


def bore_radius(result: CamResult) -> float:
    """The problem's bore radius, else ``BORE_FRACTION`` of the profile's smallest radius (mm)."""
    given = result.problem.bore_radius
    return BORE_FRACTION * float(np.linalg.norm(result.geometry.profile, axis=1).min()) if given is None else given


def write_csv(result: CamResult, path: Path) -> Path:
    g = result.geometry
    unit = "deg" if result.problem.oscillating else "mm"
    scale = np.degrees(1.0) if result.problem.oscillating else 1.0
    columns = {
        "cam_angle_deg": np.degrees(g.angle), f"displacement_{unit}": g.motion[0] * scale,
        f"velocity_{unit}_per_rad": g.motion[1] * scale, f"acceleration_{unit}_per_rad2": g.motion[2] * scale,
        f"jerk_{unit}_per_rad3": g.motion[3] * scale,
        **({"face_offset_mm": g.center[:, 0]} if result.problem.follower.kind == "flat_faced" else
           {"pitch_x_mm": g.pitch[:, 0], "pitch_y_mm": g.pitch[:, 1]}),
        "profile_x_mm": g.profile[:, 0],
        "profile_y_mm": g.profile[:, 1], "pressure_angle_deg": np.degrees(g.pressure_angle),
        "pitch_curvature_radius_mm": g.curvature_radius, "profile_curvature_radius_mm": g.profile_curvature_radius,
    }
    np.savetxt(path, np.column_stack(list(columns.values())), delimiter=",", header=",".join(columns), comments="",
               fmt="%.12g")
    return path


def cam_sheet(result: CamResult) -> Sheet:
    sheet = Sheet()
    sheet.polyline(result.geometry.profile, "OUTLINE", close=True)
    if result.problem.follower.kind != "flat_faced":
        sheet.polyline(result.geometry.pitch, "PITCH", close=True)
    sheet.circle((0.0, 0.0), result.base_radius, "CENTERLINES")
    sheet.center_cross((0.0, 0.0), 2 * result.base_radius)
    sheet.circle((0.0, 0.0), bore_radius(result), "BORE")
    sheet.diameter_dimension((0.0, 0.0), bore_radius(result), 45.0)
    sheet.title_block(TitleBlock("cam", 1, result.problem.title))
    return sheet


def write_drawings(result: CamResult, folder: str | Path) -> list[Path]:
    """``cam_profile.csv``, ``cam.dxf`` and ``cam.svg`` in ``folder`` (made if missing); the files written."""
    require_result(result, CamResult, "cam")
    return write_sheet_and_drawings(result, writable_folder(folder))[1]


def write_sheet_and_drawings(result: CamResult, folder: Path) -> tuple[Sheet, list[Path]]:
    """The files of ``write_drawings`` in the existing ``folder``: cam.dxf's sheet (for a PDF) and the files."""
    sheet, svg = cam_sheet(result), folder / "cam.svg"
    pitch = None if result.problem.follower.kind == "flat_faced" else np.vstack([result.geometry.pitch,
                                                                                 result.geometry.pitch[:1]])
    turn = np.linspace(0.0, 2 * np.pi, BORE_SEGMENTS, endpoint=False)
    write_svg(result.geometry.profile, svg, pitch_curve=pitch, bore=bore_radius(result) * np.c_[np.cos(turn),
                                                                                                   np.sin(turn)])
    return sheet, [write_csv(result, folder / "cam_profile.csv"), sheet.save(folder / "cam.dxf"), svg]

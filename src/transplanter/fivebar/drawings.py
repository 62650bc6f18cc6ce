"""What a designer takes to CAD from a five-bar design: the linkage in pose 1 as a DXF, and CSV tables.

All in millimetres and degrees (DXF INSUNITS = mm). Files:

- ``linkage.dxf``: links as centre lines (LINKS; the frame O-B on FRAME), hinge circles (HINGES,
  radius ``HINGE_FRACTION`` of the largest hinge distance), labels O A B E F P (LABELS, TEXT), the
  plate triangle E-F-P (PLATE), P over a turn (TRAJECTORY) and the key poses (KEY_POSES, labelled); with a
  seedling support, on SUPPORT: C-G-H-Z and the arm C-K at pose 1, hinges C, G, H and D, labels, and the cam's
  profile and pitch curve about D.
- with a seedling support, the cam's own ``cam_profile.csv``, ``cam.dxf`` and ``cam.svg`` (``cam.drawings``).
- ``trajectory.csv``: P over a turn from the verification (gears rolling, loop closed): carrier turn
  (clockwise from pose 1) and carrier angle (counterclockwise from +x), x, y, plate angle.
- ``relative_angle.csv``: rho (rod I against the carrier), rho' = drho/dc and the total ratio i0 = 1 / rho'.
- ``<gear>.dxf`` and ``<gear>.svg`` per gear (``gears.drawings.write_gear_drawings``): the cut tooth
  outline, the pitch curve, the bore and the assembly mark towards the mate at pose 1.
- ``pitch_curve_<gear>.csv`` per gear: polar angle, radius, x, y in the gear's own frame, as drawn on
  the carrier (``gears_on_carrier``).
"""
from __future__ import annotations

from pathlib import Path

import ezdxf
import numpy as np

from transplanter.api_arguments import require_result
from transplanter.cam.drawings import write_drawings as write_cam_drawings
from transplanter.fivebar.gears_on_carrier import gears_on_carrier, tooth_outlines
from transplanter.fivebar.result import FiveBarResult
from transplanter.fivebar.support import SupportDesign
from transplanter.gears.drawings import GearDrawing, default_bore_radius, write_gear_drawings
from transplanter.output_folder import writable_folder

#: Hinge circle radius and label height as fractions of the largest distance between two hinges in pose 1.
HINGE_FRACTION = 0.01
LABEL_FRACTION = 0.02


def pose1_points(result: FiveBarResult) -> dict[str, np.ndarray]:
    """Hinges O, A, B, E, F and the plate point P in pose 1 (mm)."""
    mech, pose1 = result.design.mech, result.problem.poses[0]
    e, f = mech.plate_points(pose1)
    return {"O": np.zeros(2), "A": mech.carrier_point(0.0), "B": np.asarray(mech.hinge_b, float), "E": e, "F": f,
            "P": pose1[:2].copy()}


def write_linkage_dxf(result: FiveBarResult, path: Path) -> Path:
    """The linkage in pose 1 with P's path and the key poses (layers in the module docstring)."""
    points = pose1_points(result)
    hinges = np.array([points[name] for name in "OABEF"])
    span = float(np.linalg.norm(hinges[:, None] - hinges[None], axis=-1).max())
    document = ezdxf.new("R2010", setup=False)
    document.units = ezdxf.units.MM
    for layer in ("LINKS", "FRAME", "HINGES", "LABELS", "PLATE", "TRAJECTORY", "KEY_POSES") + (
            ("SUPPORT",) if result.support else ()):
        document.layers.add(layer)
    space = document.modelspace()
    for start, end in ("OA", "AF", "BE"):
        space.add_line(points[start].tolist(), points[end].tolist(), dxfattribs={"layer": "LINKS"})
    space.add_line(points["O"].tolist(), points["B"].tolist(), dxfattribs={"layer": "FRAME"})
    space.add_lwpolyline([points[name].tolist() for name in "EFP"], close=True, dxfattribs={"layer": "PLATE"})
    height = LABEL_FRACTION * span
    for name, point in points.items():
        if name != "P":
            space.add_circle(point.tolist(), HINGE_FRACTION * span, dxfattribs={"layer": "HINGES"})
        space.add_text(name, height=height, dxfattribs={"layer": "LABELS", "insert": (point + height).tolist()})
    space.add_lwpolyline(result.verification.trajectory.tolist(), close=True, dxfattribs={"layer": "TRAJECTORY"})
    for label, pose in zip(result.problem.labels, result.problem.poses, strict=True):
        space.add_point(pose[:2].tolist(), dxfattribs={"layer": "KEY_POSES"})
        space.add_text(label, height=height, dxfattribs={"layer": "KEY_POSES", "insert": (pose[:2] - height).tolist()})
    if result.support:
        _support_entities(result.support, space, HINGE_FRACTION * span, height)
    document.saveas(path)
    return path


def _support_entities(support: SupportDesign, space, radius: float, height: float):
    """The support at pose 1 on layer SUPPORT: C-G-H-Z, the arm C-K, hinges, labels, the cam's profile and pitch."""
    joints = {name: points[0] for name, points in support.joints([0.0]).items()}
    attributes = {"layer": "SUPPORT"}
    space.add_lwpolyline([joints[name].tolist() for name in "CGHZ"], dxfattribs=attributes)
    space.add_line(joints["C"].tolist(), joints["K"].tolist(), dxfattribs=attributes)
    for name in "CGHDK":
        space.add_circle(joints[name].tolist(), support.spec.follower.roller_radius if name == "K" else radius,
                         dxfattribs=attributes)
    for name in "CGHZD":
        space.add_text(name, height=height, dxfattribs={**attributes, "insert": (joints[name] + height).tolist()})
    for curve in ("profile", "pitch"):
        space.add_lwpolyline(support.cam_outline(0.0, curve).tolist(), close=True, dxfattribs=attributes)


def _write_table(path: Path, columns: dict[str, np.ndarray]) -> Path:
    np.savetxt(path, np.column_stack(list(columns.values())) + 0.0, delimiter=",", header=",".join(columns),
               comments="",
               fmt="%.12g")
    return path


def write_tables(result: FiveBarResult, folder: Path) -> list[Path]:
    """trajectory.csv, relative_angle.csv and pitch_curve_<gear>.csv (columns in the module docstring)."""
    check, relative, mech = result.verification, result.design.relative_angle, result.design.mech
    turns = check.carrier_turns
    slope = relative.evaluate(turns, 1)
    written = [
        _write_table(folder / "trajectory.csv", {
            "carrier_turn_deg": np.degrees(turns), "carrier_angle_deg": np.degrees(mech.carrier_angle - turns),
            "x_mm": check.trajectory[:, 0], "y_mm": check.trajectory[:, 1],
            "plate_angle_deg": np.degrees(np.angle(np.exp(1j * check.directions)))}),
        _write_table(folder / "relative_angle.csv", {
            "carrier_turn_deg": np.degrees(turns), "rho_deg": np.degrees(relative.evaluate(turns)),
            "rho_slope": slope, "total_ratio_i0": 1 / slope})]
    for gear in gears_on_carrier(result.train, float(mech.carrier_length)):
        x, y = gear.pitch_curve.T
        written.append(_write_table(folder / f"pitch_curve_{gear.name}.csv", {
            "angle_deg": np.degrees(np.arctan2(y, x)), "radius_mm": np.hypot(x, y), "x_mm": x, "y_mm": y}))
    return written


def write_drawings(result: FiveBarResult, folder: str | Path) -> list[Path]:
    """The linkage DXF, the CSV tables, each gear's DXF and SVG (teeth, pitch curve, bore, assembly mark) and the
    support cam's files of a five-bar design in ``folder`` (made if missing); the files written."""
    require_result(result, FiveBarResult, "fivebar")
    folder = writable_folder(folder)
    gears = write_gear_drawings(gear_drawings(result, tooth_outlines(result.toothed)), folder)
    cam = write_cam_drawings(result.support.cam, folder) if result.support else []
    return [write_linkage_dxf(result, folder / "linkage.dxf"), *write_tables(result, folder), *gears, *cam]


def gear_drawings(result: FiveBarResult, outlines: dict[str, np.ndarray]) -> list[GearDrawing]:
    """The four gears to manufacture (for ``gears.drawings.write_gear_drawings``): ``outlines`` maps a gear
    name (sun, first_intermediate, second_intermediate, planet) to its tooth outline (N, 2) mm in the
    frame of ``gears_on_carrier`` (stage 1 mirrored from the gear library's); bore ``default_bore_radius``,
    mark towards the contact point at pose 1."""
    return [GearDrawing(gear.name, outlines[gear.name], gear.pitch_curve, default_bore_radius(outlines[gear.name]),
                        gear.contact_direction)
            for gear in gears_on_carrier(result.train, float(result.design.mech.carrier_length))]

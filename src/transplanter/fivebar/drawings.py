"""What a workshop takes from a five-bar design: part drawings, the assembly at pose 1, a parts list, CSV tables.

All in millimetres and degrees, every DXF in the convention of ``drawing.sheet``. Files:

- ``linkage.dxf``: the assembly at pose 1: each link plate's outline and the gears' tooth outlines in place
  (OUTLINE), the shaft and hinge holes (BORE), the links' centre lines, the frame O-B and P over a turn
  (CENTERLINES), the key poses (MARK), the labels O A B E F P and the key poses' (TEXT); with a seedling support,
  C-G-H-Z and the arm C-K at pose 1 (CENTERLINES), its hinges (BORE), labels, and the cam's profile (OUTLINE) and
  pitch curve (PITCH) about D.
- ``<part>.dxf`` per link plate (``fivebar.parts``): carrier, rod_AF, push_plate_EFP, receiving_plate_BE, with
  their holes' centre distances and diameters dimensioned.
- ``<gear>.dxf`` and ``<gear>.svg`` per gear (``drawing.gear_sheet``): the cut tooth outline, the pitch curve, the
  keyed bore of ``fivebar.shafts`` and the assembly mark towards the mate at pose 1.
- ``drawings.pdf``: every sheet above, one a page.
- ``parts.csv``: part, quantity, key dimensions, teeth, module, material (blank).
- with a seedling support, the cam's own ``cam_profile.csv``, ``cam.dxf`` and ``cam.svg`` (``cam.drawings``).
- ``trajectory.csv``: P over a turn from the verification (gears rolling, loop closed): carrier turn
  (clockwise from pose 1) and carrier angle (counterclockwise from +x), x, y, plate angle.
- ``relative_angle.csv``: rho (rod I against the carrier), rho' = drho/dc and the total ratio i0 = 1 / rho'.
- ``pitch_curve_<gear>.csv`` per gear: polar angle, radius, x, y in the gear's own frame, as drawn on
  the carrier (``gears_on_carrier``).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from transplanter.api_arguments import require_result
from transplanter.cam.drawings import write_sheet_and_drawings
from transplanter.drawing.gear_sheet import GearDrawing, draw_keyed_bore, write_gear_sheet
from transplanter.drawing.parts_list import write_parts_list
from transplanter.drawing.pdf import write_pdf
from transplanter.drawing.plate_sheet import PlatePart, plate_sheet
from transplanter.drawing.sheet import Sheet, TitleBlock
from transplanter.fivebar.gears_on_carrier import carrier_to_world, gears_on_carrier, tooth_outlines
from transplanter.fivebar.parts import link_parts
from transplanter.fivebar.result import FiveBarResult
from transplanter.fivebar.support import SupportDesign
from transplanter.output_folder import writable_folder
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.trains.toothed_train import ToothedTrain

#: Label height as a fraction of the largest distance between two hinges in pose 1.
LABEL_FRACTION = 0.02


def pose1_points(result: FiveBarResult) -> dict[str, np.ndarray]:
    """Hinges O, A, B, E, F and the plate point P in pose 1 (mm)."""
    mech, pose1 = result.design.mech, result.problem.poses[0]
    e, f = mech.plate_points(pose1)
    return {"O": np.zeros(2), "A": mech.carrier_point(0.0), "B": np.asarray(mech.hinge_b, float), "E": e, "F": f,
            "P": pose1[:2].copy()}


def parts(result: FiveBarResult) -> list[PlatePart]:
    """The four link plates (``fivebar.parts``)."""
    return link_parts(result.design.mech, result.toothed, result.shafts, result.problem.title)


#: Which hinges of pose 1 each part's first two holes sit on.
PLACED_ON = {"carrier": ("O", "A"), "rod_AF": ("A", "F"), "push_plate_EFP": ("E", "F"),
             "receiving_plate_BE": ("B", "E")}


def assembly_sheet(result: FiveBarResult) -> Sheet:
    """The assembly at pose 1 (layers in the module docstring)."""
    points = pose1_points(result)
    hinges = np.array([points[name] for name in "OABEF"])
    span = float(np.linalg.norm(hinges[:, None] - hinges[None], axis=-1).max())
    height = LABEL_FRACTION * span
    sheet = Sheet()
    for part in parts(result):
        first, second = PLACED_ON[part.name]
        motion = part.placed(points[first], points[second])
        sheet.polyline(motion(part.outline()), "OUTLINE", close=True)
        for hole in part.holes:
            if hole.diameter:
                sheet.circle(motion(hole.center[None])[0], hole.diameter / 2, "BORE")
    outlines, mech = tooth_outlines(result.toothed), result.design.mech
    bores = result.shafts.bores
    for gear in gears_on_carrier(result.train, float(mech.carrier_length)):
        sheet.polyline(carrier_to_world(mech, gear.placed(outlines[gear.name], [0.0])[0], 0.0), "OUTLINE", close=True)
        turn = float(gear.angle(np.zeros(1))[0]) + float(mech.carrier_angle)
        draw_keyed_bore(sheet, bores[gear.name], carrier_to_world(mech, gear.center[None], 0.0)[0], turn)
    for start, end in ("OA", "AF", "BE", "OB"):
        sheet.line(points[start], points[end], "CENTERLINES")
    sheet.polyline(np.array([points[name] for name in "EFP"]), "CENTERLINES", close=True)
    for name, point in points.items():
        sheet.text(name, point + height, height)
    sheet.polyline(result.verification.trajectory, "CENTERLINES", close=True)
    for label, pose in zip(result.problem.labels, result.problem.poses, strict=True):
        sheet.center_cross(pose[:2], height)
        sheet.space.add_point(pose[:2].tolist(), dxfattribs={"layer": "MARK"})
        sheet.text(label, pose[:2] - height, height)
    if result.support:
        _support_entities(result.support, sheet, result.shafts.shafts["hinge"].diameter / 2, height)
    sheet.title_block(TitleBlock("assembly at pose 1", 1, result.problem.title,
                                 module=result.toothed.module,
                                 pressure_angle_deg=float(np.degrees(result.toothed.pressure_angle))))
    return sheet


def _support_entities(support: SupportDesign, sheet: Sheet, radius: float, height: float):
    """The support at pose 1: C-G-H-Z and the arm C-K, hinges, labels, the cam's profile and pitch curve."""
    joints = {name: points[0] for name, points in support.joints([0.0]).items()}
    sheet.polyline(np.array([joints[name] for name in "CGHZ"]), "CENTERLINES")
    sheet.line(joints["C"], joints["K"], "CENTERLINES")
    for name in "CGHDK":
        sheet.circle(joints[name], support.spec.follower.roller_radius if name == "K" else radius,
                     "OUTLINE" if name == "K" else "BORE")
    for name in "CGHZD":
        sheet.text(name, joints[name] + height, height)
    sheet.polyline(support.cam_outline(0.0, "profile"), "OUTLINE", close=True)
    sheet.polyline(support.cam_outline(0.0, "pitch"), "PITCH", close=True)


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
    return written + write_pitch_curves(result.train, float(mech.carrier_length), folder)


def write_pitch_curves(train: PlanetaryTrain, carrier_length: float, folder: Path, mirrored: bool = False
                       ) -> list[Path]:
    """pitch_curve_<gear>.csv per gear of a planetary train: polar angle, radius, x, y in the gear's own frame of
    ``gears_on_carrier`` (``mirrored``: y -> -y, the parts of a carrier turning counterclockwise)."""
    flip = np.array([1.0, -1.0 if mirrored else 1.0])
    written = []
    for gear in gears_on_carrier(train, carrier_length):
        x, y = (gear.pitch_curve * flip).T
        written.append(_write_table(folder / f"pitch_curve_{gear.name}.csv", {
            "angle_deg": np.degrees(np.arctan2(y, x)), "radius_mm": np.hypot(x, y), "x_mm": x, "y_mm": y}))
    return written


def write_drawings(result: FiveBarResult, folder: str | Path) -> list[Path]:
    """The assembly, the part and gear sheets, their PDF, parts.csv, the CSV tables and the support cam's files of
    a five-bar design in ``folder`` (made if missing); the files written."""
    require_result(result, FiveBarResult, "fivebar")
    folder = writable_folder(folder)
    plates, gears = parts(result), gear_drawings(result, tooth_outlines(result.toothed))
    pages = [("linkage.dxf", assembly_sheet(result)), *((f"{part.name}.dxf", plate_sheet(part)) for part in plates)]
    sheets = [sheet.save(folder / name) for name, sheet in pages]
    files = [write_gear_sheet(gear, folder) for gear in gears]
    if result.support:
        files.append(write_sheet_and_drawings(result.support.cam, folder))
    for sheet, written in files:
        dxf = next(path for path in written if path.suffix == ".dxf")
        pages.append((dxf.name, sheet))
        sheets.append(dxf)
    others = [path for _, written in files for path in written if path.suffix != ".dxf"]
    return [*sheets, *others, write_pdf([(name, sheet.document) for name, sheet in pages], folder / "drawings.pdf"),
            write_parts_list(plates, gears, folder / "parts.csv"), *write_tables(result, folder)]


def gear_drawings(result: FiveBarResult, outlines: dict[str, np.ndarray]) -> list[GearDrawing]:
    """The four gears to make: ``outlines`` maps a gear name (sun, first_intermediate, second_intermediate,
    planet) to its tooth outline (N, 2) mm in the frame of ``gears_on_carrier`` (stage 1 mirrored from the gear
    library's); the keyed bore of ``fivebar.shafts``, its keyway on the mark towards the contact point at pose 1."""
    return toothed_gear_drawings(result.toothed, outlines, result.shafts.bores, result.problem.title)


def toothed_gear_drawings(toothed: ToothedTrain, outlines: dict[str, np.ndarray], bores: dict[str, KeyedBore],
                          title: str, mirrored: bool = False) -> list[GearDrawing]:
    """The four gears of a toothed train to make, by the names of ``gears_on_carrier``: ``outlines`` (N, 2) mm as
    ``gear_drawings`` takes them, ``bores`` with their keyways on the marks, the problem's ``title``;
    ``mirrored`` (y -> -y, the bores' directions negated): the parts of a carrier turning counterclockwise."""
    a1, a2 = toothed.train.center_distances
    teeth = {gear.name.replace(" ", "_"): gear.teeth for gear in toothed.gears}
    flip = np.array([1.0, -1.0 if mirrored else 1.0])
    drawings = []
    for gear in gears_on_carrier(toothed.train, toothed.carrier_length):
        block = TitleBlock(gear.name.replace("_", " "), 1, title, module=toothed.module,
                           teeth=teeth[gear.name], pressure_angle_deg=float(np.degrees(toothed.pressure_angle)),
                           center_distance_mm=a1 if gear.name in ("sun", "first_intermediate") else a2)
        bore = bores[gear.name]
        if mirrored:
            bore = KeyedBore(bore.diameter, bore.key, -bore.direction)
        drawings.append(GearDrawing(gear.name, outlines[gear.name] * flip, gear.pitch_curve * flip, bore, block))
    return drawings

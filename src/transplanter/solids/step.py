"""Parts as STEP solids through build123d (the optional extra ``transplanter[cad]``): a gear's tooth outline
extruded to its face width, less its keyed bore; a link plate's outline extruded to its thickness, less its holes;
a cam disc's profile extruded to its thickness, less its bore.

A gear's and a cam disc's outline go in as smooth curves (``solids.smooth_outline``): split at its corners, each
run one cubic B-spline edge, so a side face per run (a few per tooth) and no face per sampled segment, which made a
gear of the main job a 10 MB file that OpenCASCADE took a minute to read back. Every point of the outline given
lies within ``GEAR_WITHIN_MODULES`` of the module (a gear: 0.15 um at module 1.5, far below the few um of a fine
gear's profile tolerance) or ``DISC_WITHIN_EXTENT`` of the outline's extent (a disc) of the solid's edge; between
two points the edge keeps within that plus twice the chord's sagitta of the chord. The commands give a gear its
cut outline (the drawings thin it within ``geometry.outline_thinning.DRAWN_WITHIN_MODULES``): a shaper-cut outline
has a point every 0.002 module, so its solid's edge is within the bound of the cut teeth and within the drawing's
chord tolerance plus the bound of the drawn polyline. A plate keeps its polyline (its arcs' 32 segments a
quarter: about 130 faces, read back in 0.06 s).

Without build123d nothing is written and ``MISSING_NOTE`` says so. The sizes are ``solids.sizes``'; every command
writes its parts through ``solids.part_files``.
"""
from __future__ import annotations

import importlib.util
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from transplanter.drawing.gear_sheet import GearDrawing
from transplanter.drawing.plate_sheet import PlatePart
from transplanter.geometry.planar import counterclockwise
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.solids.smooth_outline import smooth_runs

#: The time stamp every STEP header gets, the one ezdxf's fixed metadata gives DXF files.
FIXED_TIME = "2000-01-01T00:00:00"
_STAMP = re.compile(r"(FILE_NAME\('[^']*',)'[^']*'")
MISSING_NOTE = "STEP solids not written: they need the optional extra transplanter[cad] (build123d)"


def cad_installed() -> bool:
    """Whether build123d can be imported (without importing it: that takes seconds)."""
    return importlib.util.find_spec("build123d") is not None


#: A gear's solid edge is within this many modules of every point of the outline it is made from.
GEAR_WITHIN_MODULES = 1e-4
#: A disc's solid edge is within this fraction of its outline's extent (largest side of its box) of every point.
DISC_WITHIN_EXTENT = 1e-5


def _face(outline: np.ndarray):
    import build123d as bd

    return bd.make_face(bd.Polyline(*map(tuple, counterclockwise(np.asarray(outline, float)).tolist()), close=True))


def _smooth_face(outline: np.ndarray, within: float):
    """The face bounded by the outline's smooth runs (``solids.smooth_outline``), every point within ``within``: the
    plane face OpenCASCADE makes on their wire, run counterclockwise so that the face looks up +Z and the part is
    extruded from z = 0 up (a clockwise wire turns the face over: the part lay below z = 0).

    ``build123d.Face(wire)`` less its plane check and its ShapeFix_Face, which looks for self-intersections among the
    hundreds of edges of a gear (0.15-0.3 s a gear) and finds nothing to fix on runs that meet end to end at the
    outline's own vertices: the solid's STEP file is the same byte for byte. Its ShapeFix_Shape of the wire stays
    (without it the edges' curves on the plane differ in their last digits)."""
    import build123d as bd
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeFace
    from OCP.ShapeFix import ShapeFix_Shape
    from OCP.TopoDS import TopoDS

    fix = ShapeFix_Shape(bd.Wire([_edge(curve) for curve in smooth_runs(counterclockwise(outline), within)]).wrapped)
    fix.Perform()
    maker = BRepBuilderAPI_MakeFace(TopoDS.Wire(fix.Shape()), True)
    if not maker.IsDone():
        raise ValueError(f"no plane face on the outline's curves: {maker.Error()}")
    return bd.Face(maker.Face())


def _edge(curve):
    """A build123d Edge of a scipy B-spline of the plane (a line where it has two coefficients): what
    ``Edge.make_line`` / ``Edge.make_bspline`` make (knots within build123d's ``TOLERANCE`` one knot of their summed
    multiplicity), built in OpenCASCADE directly; build123d takes each pole through a ``Vector`` of its own."""
    import build123d as bd
    from build123d.geometry import TOLERANCE
    from OCP.BRepBuilderAPI import BRepBuilderAPI_MakeEdge
    from OCP.collections import Array1_double, Array1_gp_Pnt, Array1_int
    from OCP.Geom import Geom_BSplineCurve
    from OCP.gp import gp_Pnt

    poles = [gp_Pnt(x, y, 0.0) for x, y in np.asarray(curve.c, float).tolist()]
    if len(poles) == 2:
        return bd.Edge(BRepBuilderAPI_MakeEdge(*poles).Edge())
    knots, multiplicities = [], []
    for knot in curve.t.tolist():
        if knots and abs(knot - knots[-1]) <= TOLERANCE:
            multiplicities[-1] += 1
        else:
            knots.append(knot)
            multiplicities.append(1)
    pole_array = Array1_gp_Pnt(1, len(poles))
    for index, pole in enumerate(poles, start=1):
        pole_array.SetValue(index, pole)
    knot_array, multiplicity_array = Array1_double(1, len(knots)), Array1_int(1, len(knots))
    for index, (knot, multiplicity) in enumerate(zip(knots, multiplicities, strict=True), start=1):
        knot_array.SetValue(index, knot)
        multiplicity_array.SetValue(index, multiplicity)
    spline = Geom_BSplineCurve(pole_array, knot_array, multiplicity_array, int(curve.k), False)
    return bd.Edge(BRepBuilderAPI_MakeEdge(spline).Edge())


def _keyed_hole(bore: KeyedBore):
    """The bore's circle and its keyway's rectangle (from the centre out to d/2 + t2), exact."""
    import build123d as bd

    middle = bore.reach / 2 * np.array([np.cos(bore.direction), np.sin(bore.direction)])
    keyway = bd.Pos(*middle) * bd.Rot(0, 0, np.degrees(bore.direction)) * bd.Rectangle(bore.reach, bore.key.width)
    return bd.Circle(bore.radius) + keyway


def gear_solid(gear: GearDrawing, face_width: float, module: float):
    """The gear's tooth outline as smooth curves within ``GEAR_WITHIN_MODULES`` of the ``module``, extruded to
    ``face_width`` mm, less its keyed bore (a build123d Part)."""
    import build123d as bd

    face = _smooth_face(gear.outline, GEAR_WITHIN_MODULES * module)
    return bd.extrude(face - _keyed_hole(gear.bore), amount=face_width)


@dataclass(frozen=True)
class BoredDisc:
    """A flat part with a plain round bore at its centre (a cam disc): its closed ``outline`` (N, 2) and
    ``bore_radius`` (mm), in its own frame (the bore's centre at the origin)."""

    name: str
    outline: np.ndarray
    bore_radius: float


def disc_solid(disc: BoredDisc, thickness: float):
    """The disc's outline as smooth curves within ``DISC_WITHIN_EXTENT`` of its extent, extruded to ``thickness`` mm,
    less its bore (a build123d Part)."""
    import build123d as bd

    within = DISC_WITHIN_EXTENT * float(np.ptp(disc.outline, axis=0).max())
    return bd.extrude(_smooth_face(disc.outline, within) - bd.Circle(disc.bore_radius), amount=thickness)


def plate_solid(part: PlatePart, thickness: float):
    """The plate's outline extruded to ``thickness`` mm, less its holes (a build123d Part)."""
    import build123d as bd

    face = _face(part.outline())
    for hole in part.holes:
        if hole.diameter:
            face -= bd.Pos(*hole.center) * bd.Circle(hole.diameter / 2)
    return bd.extrude(face, amount=thickness)


def write_step(solid, path: Path) -> Path:
    """The solid as STEP, its header's time stamp fixed (``FIXED_TIME``): the same part gives the same bytes."""
    import build123d as bd

    bd.export_step(solid, str(path))
    text = path.read_text()
    header_end = text.index("ENDSEC;")
    path.write_text(_STAMP.sub(rf"\g<1>'{FIXED_TIME}'", text[:header_end], count=1) + text[header_end:])
    return path

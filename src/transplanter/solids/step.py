"""Parts as STEP solids through build123d (the optional extra ``transplanter[cad]``): a gear's tooth outline
extruded to its face width, less its keyed bore; a link plate's outline extruded to its thickness, less its holes;
a cam disc's profile extruded to its thickness, less its bore.

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
from transplanter.shafts.keyed_bore import KeyedBore

#: The time stamp every STEP header gets, the one ezdxf's fixed metadata gives DXF files.
FIXED_TIME = "2000-01-01T00:00:00"
_STAMP = re.compile(r"(FILE_NAME\('[^']*',)'[^']*'")
MISSING_NOTE = "STEP solids not written: they need the optional extra transplanter[cad] (build123d)"


def cad_installed() -> bool:
    """Whether build123d can be imported (without importing it: that takes seconds)."""
    return importlib.util.find_spec("build123d") is not None


def _face(outline: np.ndarray):
    import build123d as bd

    return bd.make_face(bd.Polyline(*map(tuple, np.asarray(outline, float).tolist()), close=True))


def _keyed_hole(bore: KeyedBore):
    """The bore's circle and its keyway's rectangle (from the centre out to d/2 + t2), exact."""
    import build123d as bd

    middle = bore.reach / 2 * np.array([np.cos(bore.direction), np.sin(bore.direction)])
    keyway = bd.Pos(*middle) * bd.Rot(0, 0, np.degrees(bore.direction)) * bd.Rectangle(bore.reach, bore.key.width)
    return bd.Circle(bore.radius) + keyway


def gear_solid(gear: GearDrawing, face_width: float):
    """The gear's tooth outline extruded to ``face_width`` mm, less its keyed bore (a build123d Part)."""
    import build123d as bd

    return bd.extrude(_face(gear.outline) - _keyed_hole(gear.bore), amount=face_width)


@dataclass(frozen=True)
class BoredDisc:
    """A flat part with a plain round bore at its centre (a cam disc): its closed ``outline`` (N, 2) and
    ``bore_radius`` (mm), in its own frame (the bore's centre at the origin)."""

    name: str
    outline: np.ndarray
    bore_radius: float


def disc_solid(disc: BoredDisc, thickness: float):
    """The disc's outline extruded to ``thickness`` mm, less its bore (a build123d Part)."""
    import build123d as bd

    return bd.extrude(_face(disc.outline) - bd.Circle(disc.bore_radius), amount=thickness)


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

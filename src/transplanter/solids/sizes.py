"""How thick a part's solid is: a gear's face width and a link plate's thickness (mm), given in the problem file
or by the default rules.

Problem fields (the face width sits in the table that holds the module):

    [gears]                 # fivebar; [gear] in a parallelogram problem, [pair] in a gear problem
    face_width_mm = 15.0    # default FACE_WIDTH_MODULES modules (spur gears run 6 to 12)
    [plates]                # fivebar: its link plates (carrier, rod, push plate, receiving plate)
    thickness_mm = 6.0      # default PLATE_THICKNESS_PIN_DIAMETERS of the hinge pin's diameter
"""
from __future__ import annotations

from dataclasses import dataclass

from transplanter.toml_fields import ClassFields, FieldReader

FACE_WIDTH_MODULES = 10.0
PLATE_THICKNESS_PIN_DIAMETERS = 0.75


@dataclass(frozen=True)
class SolidSizes:
    """Given gear face width and plate thickness (mm); None takes the default rule."""

    face_width_mm: float | None = None
    thickness_mm: float | None = None

    def __post_init__(self):
        check = ClassFields(self)
        check.positive("face_width_mm", optional=True)
        check.positive("thickness_mm", optional=True)

    def face_width(self, module: float) -> float:
        """The given face width, else ``FACE_WIDTH_MODULES`` modules (mm)."""
        return FACE_WIDTH_MODULES * module if self.face_width_mm is None else self.face_width_mm

    def thickness(self, pin_diameter: float) -> float:
        """The given plate thickness, else ``PLATE_THICKNESS_PIN_DIAMETERS`` of the hinge pin's diameter (mm)."""
        return PLATE_THICKNESS_PIN_DIAMETERS * pin_diameter if self.thickness_mm is None else self.thickness_mm


def read_solid_sizes(read: FieldReader, gears: dict, gears_where: str, plates: dict | None = None) -> SolidSizes:
    """``face_width_mm`` of the table ``gears`` (named ``gears_where``) and, for a problem with plates,
    ``thickness_mm`` of its ``[plates]`` table; each a positive length when given (the caller checks the tables'
    other keys)."""
    face_width = read.length(gears, "face_width_mm", gears_where) if "face_width_mm" in gears else None
    thickness = None
    if plates is not None:
        read.keys(plates, {"thickness_mm"}, "plates")
        thickness = read.length(plates, "thickness_mm", "plates") if "thickness_mm" in plates else None
    return SolidSizes(face_width, thickness)

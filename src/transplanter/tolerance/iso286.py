"""ISO 286-1 limits of an H7/g6 clearance fit, the running fit of a hinge pin or a shaft in its hole.

Nominal sizes are grouped in ranges "above - up to and including" (mm); each range has its standard
tolerance grades IT6 and IT7 and the shaft's fundamental deviation g (its upper deviation es), in
micrometres. The tables cover nominal sizes above 0 and up to 500 mm (``LARGEST_MM``); a size outside them is
refused. The hole H7 lies on the nominal size, +0 / +IT7; the shaft g6 below it, es / es - IT6.

The radial play of a hinge is half the fit's largest diametral clearance (``radial_play_mm``): the play is
the limit within which a pin's centre can sit off its hole's, and any hole and pin within their limits leaves
the pin at most that far off, so the tolerance it gives is a limit as every other dimension's is (the mean
clearance would let a built hinge exceed it). Within that limit the offsets are spread as every dimension
is (``tolerance.dimensions``: uniform or normal).
"""
from __future__ import annotations

import bisect

from transplanter.errors import ProblemError

#: Upper ends of the nominal size ranges (mm); the first range starts above 0.
RANGE_TOPS_MM = (3, 6, 10, 18, 30, 50, 80, 120, 180, 250, 315, 400, 500)
LARGEST_MM = RANGE_TOPS_MM[-1]
#: Standard tolerance grades per range (um).
IT6_UM = (6, 8, 9, 11, 13, 16, 19, 22, 25, 29, 32, 36, 40)
IT7_UM = (10, 12, 15, 18, 21, 25, 30, 35, 40, 46, 52, 57, 63)
#: Fundamental deviation g of a shaft, its upper deviation es, per range (um).
G_UPPER_UM = (-2, -4, -5, -6, -7, -9, -10, -12, -14, -15, -17, -18, -20)
FIT = "H7/g6"


def _range_index(diameter_mm: float, field: str) -> int:
    if not 0 < diameter_mm <= LARGEST_MM:
        raise ProblemError(f"{field} = {diameter_mm:g} mm: ISO 286 tables here cover {FIT} fits on diameters "
                           f"above 0 and up to {LARGEST_MM} mm")
    return bisect.bisect_left(RANGE_TOPS_MM, diameter_mm)


def hole_h7_um(diameter_mm: float, field: str = "diameter") -> tuple[int, int]:
    """Lower and upper deviation (um) of an H7 hole of nominal ``diameter_mm``."""
    return 0, IT7_UM[_range_index(diameter_mm, field)]


def shaft_g6_um(diameter_mm: float, field: str = "diameter") -> tuple[int, int]:
    """Lower and upper deviation (um) of a g6 shaft of nominal ``diameter_mm``."""
    i = _range_index(diameter_mm, field)
    return G_UPPER_UM[i] - IT6_UM[i], G_UPPER_UM[i]


def clearance_um(diameter_mm: float, field: str = "diameter") -> tuple[int, int]:
    """Smallest and largest diametral clearance (um) of the H7/g6 fit: hole's lower minus shaft's upper
    deviation, and hole's upper minus shaft's lower."""
    hole, shaft = hole_h7_um(diameter_mm, field), shaft_g6_um(diameter_mm, field)
    return hole[0] - shaft[1], hole[1] - shaft[0]


def radial_play_mm(diameter_mm: float, field: str = "diameter") -> float:
    """Radial play (mm) of an H7/g6 hinge of nominal ``diameter_mm``: half the largest diametral clearance
    (the module docstring says why)."""
    return clearance_um(diameter_mm, field)[1] / 2 / 1000

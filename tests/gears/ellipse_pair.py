"""A 20-tooth ellipse pair of module 2 and its two swept outlines: the shaper-cut driver and the driven gear the
driver's teeth sweep (tests of the swept-teeth envelope)."""
import numpy as np

from transplanter.gears import swept_teeth
from transplanter.gears.pair import GearPairDesign, design_pair
from transplanter.gears.pitch_curves import ellipse
from transplanter.gears.teeth import driven_table, driver_table

MODULE, ALPHA, CUTTER_TEETH = 2.0, np.radians(20), 16
#: The two outlines, as the tests' parameters name them.
GEARS = ("shaper-cut driver", "driven gear swept by the driver")


def ellipse_pair() -> GearPairDesign:
    curve = ellipse(1.0, 0.25)
    return design_pair(curve.scaled(20 * np.pi * MODULE / design_pair(curve, 1).perimeters[0]), 1)


def driver_outline(design: GearPairDesign) -> np.ndarray:
    """The shaper-cut driver's outline."""
    return swept_teeth.shaper_profile(driver_table(design), MODULE, ALPHA, CUTTER_TEETH)


def swept_outline(gear: str, design: GearPairDesign, driver: np.ndarray) -> np.ndarray:
    """The outline of ``gear`` (one of ``GEARS``) cut as the package cuts it, the driven gear swept by ``driver``
    (``driver_outline``, cut beforehand)."""
    if gear == GEARS[0]:
        return driver_outline(design)
    return swept_teeth.mate_profile(design, driver, driven_table(design), MODULE)

"""The designed mechanism's gear pair through the gear library (``transplanter.gears``): the
denatured limacon driver with m12 from eq (2), a driven gear of order 1 closed by its center
distance, tooth counts at the module and, given whole teeth, tooth outlines for the drawings.

Scaling the pair to whole teeth changes b, l and a in one ratio; the driven angle depends on
b/l and a/l only (derivations/parallelogram.py), so the trajectory is unchanged.
"""
from __future__ import annotations

import numpy as np

from transplanter.gears.result import GearResult


def gear_pair(design: dict, module: float, pressure_angle: float, driver_speed: float, teeth: int | None = None,
              source: str = "<design>") -> GearResult:
    """The gear library's pair for a design (mm, rad): closure, curvature, counts, teeth when ``teeth``."""
    from transplanter import gears

    pair = {"driven_order": 1, "module": module, "pressure_angle_deg": float(np.degrees(pressure_angle)),
            "driver_speed_rpm": driver_speed * 60 / (2 * np.pi)}
    if teeth is not None:
        pair["teeth"] = int(teeth)
    driver = {"family": "denatured_limacon", "base": design["l"], "amplitude": design["b"], "m11": design["m11"]}
    return gears.synthesize(gears.parse_problem({"driver": driver, "pair": pair}, source))

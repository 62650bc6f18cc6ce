"""Default shaft diameters, and the check that a gear's keyed bore leaves a rim under its teeth.

Rules (mm, N m):

- by torque, where the design has loads: the smallest standard diameter at least (16 T / (pi tau))^(1/3), the
  solid shaft in pure torsion at the peak torque T with ``TORSION_STRESS_MPA``, a low allowable stress that leaves
  room for bending and the keyseat's notch;
- by gear size, where it has none: the largest standard diameter at most ``GEAR_SIZE_FRACTION`` of the gear's
  root radius (its smallest outline radius);
- hinge pins by force, where the design has loads: the smallest standard diameter that carries the peak hinge
  force F (N) in single shear, 4 F / (pi d^2) <= ``PIN_SHEAR_STRESS_MPA``, and bears it on the plate's hole,
  F / (d t) <= ``PIN_BEARING_PRESSURE_MPA`` (t the plate's thickness, by default ``PLATE_THICKNESS_PIN_DIAMETERS``
  d): low allowables of a pin that turns in its hole under a load that changes over the turn;
- the check: the keyway's bottom (d/2 + t2) at least ``MIN_RIM_TOOTH_HEIGHTS`` tooth heights (2.25 modules) inside
  the root, the backup ratio of a rim that does not crack under the teeth (AGMA 2001).
"""
from __future__ import annotations

import numpy as np

from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.keys import STANDARD_DIAMETERS
from transplanter.solids.sizes import PLATE_THICKNESS_PIN_DIAMETERS

TORSION_STRESS_MPA = 20.0
PIN_SHEAR_STRESS_MPA = 40.0
PIN_BEARING_PRESSURE_MPA = 20.0
GEAR_SIZE_FRACTION = 0.8
MIN_RIM_TOOTH_HEIGHTS = 1.2
TOOTH_HEIGHT_MODULES = 2.25


def diameter_for_torque(torque_nm: float) -> float:
    """The smallest standard diameter that carries ``torque_nm`` at ``TORSION_STRESS_MPA`` (mm)."""
    needed = np.cbrt(16 * abs(torque_nm) * 1e3 / (np.pi * TORSION_STRESS_MPA))
    return float(next((d for d in STANDARD_DIAMETERS if d >= needed), STANDARD_DIAMETERS[-1]))


def diameter_for_pin(force_n: float, thickness_mm: float | None = None) -> float:
    """The smallest standard diameter whose pin carries ``force_n`` in single shear and bears it on a plate
    ``thickness_mm`` thick (None: ``PLATE_THICKNESS_PIN_DIAMETERS`` of the diameter) (mm)."""
    def carries(d: float) -> bool:
        t = PLATE_THICKNESS_PIN_DIAMETERS * d if thickness_mm is None else thickness_mm
        return (4 * abs(force_n) / (np.pi * d**2) <= PIN_SHEAR_STRESS_MPA
                and abs(force_n) / (d * t) <= PIN_BEARING_PRESSURE_MPA)

    return float(next((d for d in STANDARD_DIAMETERS if carries(d)), STANDARD_DIAMETERS[-1]))


def diameter_for_gear(root_radius: float) -> float:
    """The largest standard diameter at most ``GEAR_SIZE_FRACTION`` of ``root_radius`` (mm), else the smallest."""
    fitting = [d for d in STANDARD_DIAMETERS if d <= GEAR_SIZE_FRACTION * root_radius]
    return float(fitting[-1] if fitting else STANDARD_DIAMETERS[0])


def min_rim(module: float) -> float:
    """The least rim (mm) between the keyway's bottom and the root."""
    return MIN_RIM_TOOTH_HEIGHTS * TOOTH_HEIGHT_MODULES * module


def rim_failures(name: str, root_radius: float, bore: KeyedBore, module: float) -> list[str]:
    """One failure, with the numbers, when the keyway of ``bore`` reaches closer than ``min_rim`` to the root."""
    rim = root_radius - bore.reach
    if rim >= min_rim(module):
        return []
    return [f"{name}: a {bore.diameter:g} mm bore's keyway reaches {bore.reach:.3f} mm from the centre, leaving "
            f"{rim:.3f} mm to the root at {root_radius:.3f} mm; at least {min_rim(module):.3f} mm expected "
            f"({MIN_RIM_TOOTH_HEIGHTS:g} tooth heights at module {module:g})"]

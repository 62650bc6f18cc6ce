"""The gear pair as constraints of the search, for many designs at once (gear library formulas).

- Closure: the center distance is solved (``kinematics.closing_center_distance``), never free.
- Convexity of both pitch curves: the gear library's derived polynomials in C = cos(m phi)
  (``limacon_driver_convexity``, ``limacon_driven_convexity``, the onion-transplanter paper's eq 9-10 done right), for
  each half (m11, m12) on a grid of C in [-1, 1]; convex where positive.
- Undercut at the module: the curvature radius (eq 8, ``polar_curvature``) of both curves, the
  driven one through ``conjugate_pitch``, at least addendum * m / sin^2(pressure angle), the
  rack criterion the gear library applies when it cuts teeth (gears/teeth.py). On the half
  r1 = l + b C the slope is b m sqrt(1 - C^2) up to sign and the bend -b m^2 C.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.gears import (
    conjugate_pitch,
    limacon_driven_convexity,
    limacon_driver_convexity,
    polar_curvature,
)
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.generated import numpy_twin

_driver_convexity = numpy_twin(limacon_driver_convexity)
_driven_convexity = numpy_twin(limacon_driven_convexity)
_curvature = numpy_twin(polar_curvature)
_conjugate = numpy_twin(conjugate_pitch)
COSINES = np.cos(np.linspace(0.0, np.pi, 97))


def undercut_limit(module: float, pressure_angle: float) -> float:
    """Smallest curvature radius (mm) a rack of this module cuts without undercut."""
    return ADDENDUM * module / np.sin(pressure_angle) ** 2


@dataclass(frozen=True)
class GearMargins:
    """Per design (shape (P,)): smallest convexity (scale-free) and curvature radius (mm) of each gear."""

    driver_convexity: np.ndarray
    driven_convexity: np.ndarray
    driver_curvature: np.ndarray
    driven_curvature: np.ndarray


def gear_margins(m11, m12, amplitude, base_radius, center_distance) -> GearMargins:
    """Convexity and curvature margins of the pairs (arrays of shape (P,)); the driver's half is
    r1 = base_radius + amplitude cos(m phi1) (the onion-transplanter paper's l and b)."""
    b, base, a = (np.asarray(v, float)[:, None] for v in (amplitude, base_radius, center_distance))
    c = COSINES[None, :]
    k, d = b / base, a / base
    driver, driven, rho1, rho2 = [], [], [], []
    for m in (np.asarray(m11, float)[:, None], np.asarray(m12, float)[:, None]):
        driver.append(_driver_convexity([k], [m], [c])[0][0].min(axis=1))
        driven.append(_driven_convexity([k], [m], [d], [c])[0][0].min(axis=1))
        radius, slope, bend = np.broadcast_arrays(base + b * c, b * m * np.sqrt(1 - c**2), -b * m**2 * c)
        with np.errstate(divide="ignore", invalid="ignore"):
            rho1.append(_curvature([radius], [slope], [bend])[0][0].min(axis=1))
            r2, s2, b2, _ = (v[0] for v in _conjugate([np.broadcast_to(a, radius.shape)], [radius], [slope], [bend]))
            rho2.append(_curvature([r2], [s2], [b2])[0][0].min(axis=1))
    return GearMargins(np.minimum(*driver), np.minimum(*driven), np.minimum(*rho1), np.minimum(*rho2))

"""General tolerances of ISO 2768-1, class m (medium): the default a drawing without its own tolerance gets.

Linear dimensions take a symmetric limit by their nominal size; angles take one by the length of the
shorter leg that carries them. Sizes below 0.5 mm have no general tolerance in the standard.
"""
from __future__ import annotations

import numpy as np

from transplanter.errors import ProblemError

#: (largest nominal size in the class, +- limit), mm, class m.
LINEAR_MM = ((3.0, 0.1), (6.0, 0.1), (30.0, 0.2), (120.0, 0.3), (400.0, 0.5), (1000.0, 0.8), (2000.0, 1.2),
             (4000.0, 2.0))
#: (longest shorter leg in the class, +- limit), mm and deg, class m.
ANGULAR_DEG = ((10.0, 1.0), (50.0, 0.5), (120.0, 1 / 3), (400.0, 1 / 6), (np.inf, 1 / 12))
SMALLEST_MM = 0.5


def _lookup(table, size: float, what: str) -> float:
    for largest, limit in table:
        if SMALLEST_MM <= size <= largest:
            return limit
    raise ProblemError(f"ISO 2768-m has no general tolerance for a {what} of {size:g} mm "
                       f"(expected {SMALLEST_MM:g} to {table[-1][0]:g} mm): give its tolerance in [tolerances]")


def linear_limit_mm(size_mm: float) -> float:
    """+- limit (mm) of a linear dimension of nominal ``size_mm``."""
    return _lookup(LINEAR_MM, abs(size_mm), "length")


def angular_limit_deg(shorter_leg_mm: float) -> float:
    """+- limit (deg) of an angle whose shorter leg is ``shorter_leg_mm`` long."""
    return _lookup(ANGULAR_DEG, abs(shorter_leg_mm), "leg")

"""Plane vectors shared by the derivations (sympy)."""
from __future__ import annotations

import sympy as sp


def unit(angle) -> sp.Matrix:
    """The column (cos, sin) of ``angle``."""
    return sp.Matrix([sp.cos(angle), sp.sin(angle)])

"""Plane vectors shared by the derivations (sympy)."""
from __future__ import annotations

import sympy as sp


def unit(angle) -> sp.Matrix:
    """The column (cos, sin) of ``angle``."""
    return sp.Matrix([sp.cos(angle), sp.sin(angle)])


def rotate(angle, vector) -> sp.Matrix:
    """The column ``vector`` turned counterclockwise by ``angle``."""
    return sp.Matrix([[sp.cos(angle), -sp.sin(angle)], [sp.sin(angle), sp.cos(angle)]]) * vector


def cross(u, v):
    """z component of u x v for 2-element columns."""
    return u[0] * v[1] - u[1] * v[0]

"""The rocker-slider of the seedling-support mechanism of Wang et al. 2025 (Figure 11, eq 14-15).

The oscillating bar turns about C; its arm C-G (length l_CG, angle theta_CG from +x) carries the
rod G-H (length l_GH) whose end H is the top of the support plate H-Z, which slides vertically at
x = x_Z. Eq (14) chains C -> G -> H with H = (x_Z, y_H); eliminating theta_GH by |H - G| = l_GH
leaves, with d = H - C,
    |d|^2 + l_CG^2 - l_GH^2 - 2 l_CG (d_x cos theta_CG + d_y sin theta_CG) = 0,
i.e. P + Q cos theta_CG + R sin theta_CG = 0, solved by theta_CG = atan2(R, Q) +- acos(-P / sqrt(Q^2 + R^2))
(the two assemblies) where |P| <= sqrt(Q^2 + R^2). The swing between the plate's two heights is
psi = theta_CG1 - theta_CG2 (eq 15).
"""
from __future__ import annotations

import sympy as sp

from derivations.spec import Derived, symbol_group


def rocker_closure(pivot, rocker, rod, slider_point, angle):
    """|C + l_CG e(theta) - H|^2 - l_GH^2 (zero where the chain C-G-H closes)."""
    gap = sp.Matrix(pivot) + rocker * sp.Matrix([sp.cos(angle), sp.sin(angle)]) - sp.Matrix(slider_point)
    return sp.expand(gap.dot(gap) - rod**2)


def closure_parts(pivot, rocker, rod, slider_point):
    """(P, Q, R) of the closure written as P + Q cos(theta) + R sin(theta)."""
    theta, c, s = sp.symbols("theta c s", real=True)
    expr = sp.expand(rocker_closure(pivot, rocker, rod, slider_point, theta).subs({sp.cos(theta): c, sp.sin(theta): s}))
    expr = sp.expand(expr.subs(s**2, 1 - c**2))
    q, r = expr.coeff(c), expr.coeff(s)
    return sp.expand(expr - q * c - r * s), q, r


def derive() -> list[Derived]:
    cx, cy, rocker, rod = symbol_group("linkage", 4)
    hx, hy = symbol_group("slider_point", 2)
    angle = symbol_group("rocker_angle", 1)[0]
    parts = closure_parts((cx, cy), rocker, rod, (hx, hy))
    return [
        Derived(name="support_rocker_closure",
                doc=("Eq (14) with theta_GH eliminated: |C + l_CG e(theta_CG) - H|^2 - l_GH^2; linkage = "
                     "(x_C, y_C, l_CG, l_GH), slider_point = H."),
                inputs=(("linkage", (cx, cy, rocker, rod)), ("slider_point", (hx, hy)), ("rocker_angle", (angle,))),
                outputs=(("residual", (rocker_closure((cx, cy), rocker, rod, (hx, hy), angle),)),)),
        Derived(name="support_rocker_parts",
                doc=("P, Q, R of the closure P + Q cos(theta_CG) + R sin(theta_CG) = 0; "
                     "linkage = (x_C, y_C, l_CG, l_GH)."),
                inputs=(("linkage", (cx, cy, rocker, rod)), ("slider_point", (hx, hy))),
                outputs=(("parts", parts),)),
    ]

"""Burmester theory of an RR dyad guiding a body through given poses (Wang et al. 2025, eq 1-2).

Notation. Pose i of the body: position d_i = (x_i, y_i) of its reference point and
orientation angle theta_i. The displacement from pose 1 to pose i maps a point z
of the pose-1 plane to d_i + Q_i (z - d_1), with Q_i the rotation by theta_i - theta_1.
A dyad has its fixed pivot (center point) G and its moving pivot, given by its
position M_1 in pose 1 (circle point); in pose i the moving pivot is
M_i = d_i + Q_i (M_1 - d_1).

Eq (1) (constant link length), halved:
    f_i(G, M_1) = (|M_i - G|^2 - |M_1 - G|^2) / 2 = 0,   i = 2..n.
After cos^2 + sin^2 = 1 the quadratic terms in M_1 cancel, so f_i is bilinear:
affine in M_1 for fixed G and affine in G for fixed M_1. Everything below follows.

- 3 poses: two affine equations fix the center for a chosen circle point, or the
  circle point for a chosen center (``dyad_rows_in_center``, ``dyad_rows_in_circle``).
- 4 poses: three equations affine in M_1 are consistent iff det [rows | constant] = 0,
  a cubic in G: the center-point curve. Symmetrically the circle-point curve in M_1.
  Both come out circular cubics of the form of eq (2).
- 5 poses: the Burmester points are the common points of the center-point curves of
  poses (1,2,3,4) and (1,2,3,5). Both pass through the pole P12, so every line
  G = P12 + t (p, q) through it meets each curve in t = 0 and in the roots of a
  quadratic (``circular_cubic_pencil``). The two quadratics share a root iff their
  resultant vanishes: a binary form of degree 8 in (p, q) that has the factor
  p^2 + q^2 (both curves pass through the circular points). The remaining degree-6
  polynomial in tau = q / p (``circular_cubic_pencil_resultant``) has as roots the
  directions of P13, P23 and of the (0, 2 or 4 real) Burmester points: a complete,
  non-iterative elimination.
"""
from __future__ import annotations

import sympy as sp

from derivations.spec import Derived, symbol_group

# Symbols of the pose-pair condition: the relative rotation enters as (c, s).
_c, _s = sp.symbols("c s", real=True)


def _pose_pair_condition(first_pose, pose, center, circle, c=_c, s=_s):
    """f_i of eq (1), expanded and reduced with s^2 = 1 - c^2 (c, s of theta_i - theta_1)."""
    x1, y1, _ = first_pose
    xi, yi, _ = pose
    g = sp.Matrix(center)
    m1 = sp.Matrix(circle)
    q = sp.Matrix([[c, -s], [s, c]])
    mi = sp.Matrix([xi, yi]) + q * (m1 - sp.Matrix([x1, y1]))
    f = sp.expand(((mi - g).dot(mi - g) - (m1 - g).dot(m1 - g)) / 2)
    return sp.expand(f.subs(s**2, 1 - c**2))


def _relative_rotation(first_pose, pose):
    angle = pose[2] - first_pose[2]
    return {_c: sp.cos(angle), _s: sp.sin(angle)}


def _affine_parts(expr, variables):
    """Coefficients of ``variables`` and the constant term of an expression affine in them."""
    poly = sp.Poly(expr, *variables)
    assert poly.total_degree() <= 1, "expected an affine expression"
    return [poly.coeff_monomial(v) for v in variables], poly.coeff_monomial(1)


def circular_cubic(h, x, y):
    """Eq (2): H1 (x^3 + x y^2) + H2 (y^3 + y x^2) + H3 x^2 + H4 y^2 + H5 x y + H6 x + H7 y + H8."""
    return (h[0] * (x**3 + x * y**2) + h[1] * (y**3 + y * x**2) + h[2] * x**2
            + h[3] * y**2 + h[4] * x * y + h[5] * x + h[6] * y + h[7])


_CUBIC_MONOMIALS = ((3, 0), (0, 3), (2, 0), (0, 2), (1, 1), (1, 0), (0, 1), (0, 0))


def cubic_coefficients(poly: sp.Poly, x, y):
    """H1..H8 of eq (2) read off a polynomial in (x, y); H1 from x^3, H2 from y^3."""
    return [poly.coeff_monomial(x**i * y**j) for i, j in _CUBIC_MONOMIALS]


def consistency_determinant(poses, solve_for: str, point):
    """det of the three pose-pair conditions of 4 poses as affine in the other pivot.

    ``solve_for="center"`` eliminates the circle point and returns a cubic in the
    center ``point``; ``"circle"`` eliminates the center and returns a cubic in the circle point.
    Pose-relative rotations are kept as symbols c_k, s_k; returns (det as a polynomial in
    ``point``, {c_k: cos, s_k: sin}). The 3x3 determinant is expanded by its first row in
    polynomial arithmetic (a few times faster than expanding expressions, the same coefficients).
    """
    other = sp.symbols("eliminated_x eliminated_y", real=True)
    rows, trig = [], {}
    for k, pose in enumerate(poses[1:], start=2):
        c_k, s_k = sp.symbols(f"c{k} s{k}", real=True)
        rel = _relative_rotation(poses[0], pose)
        trig.update({c_k: rel[_c], s_k: rel[_s]})
        if solve_for == "center":
            f = _pose_pair_condition(poses[0], pose, point, other, c_k, s_k)
        else:
            f = _pose_pair_condition(poses[0], pose, other, point, c_k, s_k)
        coefficients, constant = _affine_parts(f, other)
        rows.append([sp.Poly(entry, *point) for entry in (*coefficients, constant)])
    (a, b, c), (d, e, f), (g, h, i) = rows
    return a * (e * i - f * h) - b * (d * i - f * g) + c * (d * h - e * g), trig


def _pose_symbols(count):
    xs, ys, angles = symbol_group("pose_x", count), symbol_group("pose_y", count), symbol_group("pose_angle", count)
    return (xs, ys, angles), [tuple(p) for p in zip(xs, ys, angles, strict=True)]


def _cubic_curve(solve_for: str) -> Derived:
    groups, poses = _pose_symbols(4)
    x, y = sp.symbols("curve_x curve_y", real=True)
    det, trig = consistency_determinant(poses, solve_for, (x, y))
    # c_k, s_k are plain symbols: xreplace swaps them for the cosines and sines as subs does (the same
    # expressions), without subs's search of every subexpression (2.5 s of the module's 4 s)
    h = [sp.expand(coefficient).xreplace(trig) for coefficient in cubic_coefficients(det, x, y)]
    pivot = "center point (fixed pivot)" if solve_for == "center" else "circle point (moving pivot in pose 1)"
    return Derived(
        name=f"burmester_{solve_for}_cubic",
        doc=f"Coefficients H1..H8 (eq 2) of the {pivot} curve of four poses.",
        inputs=(("pose_x", groups[0]), ("pose_y", groups[1]), ("pose_angle", groups[2])),
        outputs=(("coefficients", tuple(h)),),
    )


def _pose_pair_rows(solve_for: str) -> Derived:
    first, pose = symbol_group("first_pose", 3), symbol_group("pose", 3)
    known = symbol_group("circle" if solve_for == "center" else "center", 2)
    unknown = sp.symbols("unknown_x unknown_y", real=True)
    if solve_for == "center":
        f = _pose_pair_condition(first, pose, unknown, known)
    else:
        f = _pose_pair_condition(first, pose, known, unknown)
    coefficients, constant = _affine_parts(f, unknown)
    rel = _relative_rotation(first, pose)
    other = "circle point" if solve_for == "center" else "center point"
    return Derived(
        name=f"dyad_rows_in_{solve_for}",
        doc=(f"Eq (1) for the pose pair (1, i) as an affine equation in the {solve_for} point "
             f"for a known {other}: coefficients . {solve_for} + constant = 0. Poses are (x, y, angle)."),
        inputs=(("first_pose", first), ("pose", pose), (("circle" if solve_for == "center" else "center"), known)),
        outputs=(("coefficients", tuple(e.subs(rel) for e in coefficients)), ("constant", (constant.subs(rel),))),
    )


def _dyad_constraint() -> Derived:
    first, pose = symbol_group("first_pose", 3), symbol_group("pose", 3)
    center, circle = symbol_group("center", 2), symbol_group("circle", 2)
    f = _pose_pair_condition(first, pose, center, circle).subs(_relative_rotation(first, pose))
    return Derived(
        name="dyad_constraint",
        doc="Eq (1) halved, (|M_i - G|^2 - |M_1 - G|^2) / 2, for the pose pair (1, i).",
        inputs=(("first_pose", first), ("pose", pose), ("center", center), ("circle", circle)),
        outputs=(("residual", (f,)),),
    )


def pencil_quadratic(h, pivot, direction):
    """(alpha, beta, gamma): cubic on G = pivot + t direction, divided by t (pivot on the curve)."""
    t = sp.Symbol("t")
    poly = sp.Poly(sp.expand(circular_cubic(h, pivot[0] + t * direction[0], pivot[1] + t * direction[1])), t)
    return [poly.coeff_monomial(t**k) for k in (3, 2, 1)]


def _pencil() -> Derived:
    h, pivot, direction = symbol_group("cubic", 8), symbol_group("pivot", 2), symbol_group("direction", 2)
    return Derived(
        name="circular_cubic_pencil",
        doc=("For a circular cubic (eq 2) through ``pivot``, the line pivot + t * direction meets it "
             "again where alpha t^2 + beta t + gamma = 0."),
        inputs=(("cubic", h), ("pivot", pivot), ("direction", direction)),
        outputs=(("quadratic", tuple(pencil_quadratic(h, pivot, direction))),),
    )


def pencil_resultant(h, k, pivot, tau):
    """Resultant in t of the two pencil quadratics on direction (1, tau), divided by 1 + tau^2.

    Returns (quotient polynomial in tau, remainder); the remainder is identically zero. Built in
    polynomial arithmetic in tau (tens of times faster than expanding the expression, the same
    coefficients).
    """
    a1, b1, c1 = (sp.Poly(e, tau) for e in pencil_quadratic(h, pivot, (1, tau)))
    a2, b2, c2 = (sp.Poly(e, tau) for e in pencil_quadratic(k, pivot, (1, tau)))
    resultant = (a1 * c2 - a2 * c1) ** 2 - (a1 * b2 - a2 * b1) * (b1 * c2 - b2 * c1)
    return sp.div(resultant, sp.Poly(1 + tau**2, tau))


def _pencil_resultant() -> Derived:
    h, k, pivot = symbol_group("first_cubic", 8), symbol_group("second_cubic", 8), symbol_group("pivot", 2)
    tau = sp.Symbol("tau")
    quotient, _ = pencil_resultant(h, k, pivot, tau)
    coefficients = tuple(quotient.coeff_monomial(tau**d) for d in range(6, -1, -1))
    return Derived(
        name="circular_cubic_pencil_resultant",
        doc=("Coefficients (tau^6 .. tau^0) of the polynomial whose roots tau = q / p are the directions "
             "from ``pivot`` (a common point) to the other common points of two circular cubics."),
        inputs=(("first_cubic", h), ("second_cubic", k), ("pivot", pivot)),
        outputs=(("polynomial", coefficients),),
    )


def _pivot_distance() -> Derived:
    first, pose = symbol_group("first_pose", 3), symbol_group("pose", 3)
    center, circle = symbol_group("center", 2), symbol_group("circle", 2)
    angle = pose[2] - first[2]
    q = sp.Matrix([[sp.cos(angle), -sp.sin(angle)], [sp.sin(angle), sp.cos(angle)]])
    moving = sp.Matrix(pose[:2]) + q * (sp.Matrix(circle) - sp.Matrix(first[:2]))
    offset = moving - sp.Matrix(center)
    return Derived(
        name="dyad_pivot_distance",
        doc="|M_i - G|: distance between the fixed pivot and the moving pivot carried to pose i.",
        inputs=(("first_pose", first), ("pose", pose), ("center", center), ("circle", circle)),
        outputs=(("distance", (sp.sqrt(offset.dot(offset)),)),),
    )


def derive() -> list[Derived]:
    return [
        _dyad_constraint(),
        _pose_pair_rows("center"),
        _pose_pair_rows("circle"),
        _pivot_distance(),
        _cubic_curve("center"),
        _cubic_curve("circle"),
        _pencil(),
        _pencil_resultant(),
    ]

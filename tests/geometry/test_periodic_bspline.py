"""The periodic cubic B-spline (``geometry.periodic_bspline``): its kernel against sympy's Cox-de Boor basis, and
the segment form against the kernel sum."""
import numpy as np
import sympy as sp

from transplanter.geometry.periodic_bspline import basis_matrix, evaluate, kernel


def test_kernel_is_the_cox_de_boor_cubic_basis():
    """Wang et al. 2025 eq (6) on uniform knots: sympy's recursion gives the centered kernel, piece by piece."""
    x = sp.Symbol("x")
    recursion = sp.bspline_basis(3, tuple(range(-2, 3)), 0, x)
    for u in np.linspace(-2.5, 2.5, 41):
        assert abs(float(recursion.subs(x, u)) - kernel(np.array(u))) < 1e-14
    for order in (1, 2):
        derivative = sp.diff(recursion, x, order)
        for u in (-1.7, -0.3, 0.4, 1.2):
            assert abs(float(derivative.subs(x, u)) - kernel(np.array(u), order)) < 1e-12


def test_segment_form_matches_the_kernel_sum(rng):
    q = rng.normal(size=12)
    x = rng.uniform(-1, 8, 200)
    for order in range(4):
        assert np.abs(basis_matrix(x, 12, order) @ q - evaluate(x, q, order)).max() < 1e-12

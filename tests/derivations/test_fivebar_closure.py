"""Wang et al. 2025 eq (7)-(10): the five-bar closure, its half-angle quadratic and discriminant.

Eq (8) as printed is the derived closure. The printed A1 of eq (9) is not: it carries
-2 L1 L4 cos(theta1) - 2 L2 L4 cos(theta2) where the derivation has + (A - A1 = 4 L4 (L1 cos
theta1 + L2 cos theta2)); the printed B1 is -B (the sign of t = tan(theta4/2) flipped, which
alone would be harmless); C1 = C. With the printed A1 the quadratic's roots miss theta4 of a
five-bar that closes, and its discriminant misjudges which crank positions can close.
"""
import numpy as np
import sympy as sp

from derivations import fivebar
from tests.published_script import reproduce
from transplanter.generated import casadi_function

L = sp.symbols("L1:6", positive=True)
T1, T2, T4, T5 = sp.symbols("theta1 theta2 theta4 theta5", real=True)
quadratic = casadi_function("fivebar", "fivebar_half_angle_quadratic")
discriminant = casadi_function("fivebar", "fivebar_discriminant")
closure = casadi_function("fivebar", "fivebar_closure")


def _published(l1, l2, l3, l4, l5, t1, t2, t5, lib=sp):
    """Eq (9) coefficients as printed in Wang et al. 2025 (the script's transcription)."""
    return reproduce.printed_eq9((l1, l2, l3, l4, l5), (t1, t2, t5), lib)


def test_printed_eq8_is_the_derived_closure():
    printed = (L[0]**2 + L[1]**2 - L[2]**2 + L[3]**2 + L[4]**2 + 2 * L[0] * L[4] * sp.cos(T1 + T5)
               + 2 * L[1] * L[4] * sp.cos(T2 + T5) - 2 * L[3] * L[4] * sp.cos(T4 + T5) + 2 * L[0] * L[1] * sp.cos(T1 - T2)
               - 2 * L[0] * L[3] * sp.cos(T1 - T4) - 2 * L[1] * L[3] * sp.cos(T2 - T4))
    assert sp.simplify(sp.expand_trig(fivebar.closure(L, T1, T2, T4, T5) - printed)) == 0


def test_printed_eq9_coefficients_against_the_derivation():
    a, b, c = fivebar.half_angle_quadratic(L, T1, T2, T5)
    a1, b1, c1 = _published(*L, T1, T2, T5)
    assert sp.simplify(sp.expand_trig(a - a1 - 4 * L[3] * (L[0] * sp.cos(T1) + L[1] * sp.cos(T2)))) == 0
    assert sp.simplify(sp.expand_trig(b + b1)) == 0
    assert sp.simplify(sp.expand_trig(c - c1)) == 0


def _closed_fivebar(rng):
    """Lengths and angles of a five-bar that closes: L3 is whatever the chosen angles leave."""
    l1, l2, l4, l5 = rng.uniform(0.5, 2.0, 4)
    t1, t2, t4, t5 = rng.uniform(-np.pi, np.pi, 4)
    e = lambda t: np.array([np.cos(t), np.sin(t)])
    gap = l1 * e(t1) + l2 * e(t2) - l5 * np.array([-np.cos(t5), np.sin(t5)]) - l4 * e(t4)
    return np.array([l1, l2, np.linalg.norm(gap), l4, l5]), (t1, t2, t4, t5)


def test_derived_quadratic_recovers_theta4_and_the_printed_one_does_not(rng):
    misses = 0
    for _ in range(50):
        lengths, (t1, t2, t4, t5) = _closed_fivebar(rng)
        assert abs(float(closure(lengths, [t1, t2, t4, t5]))) < 1e-12
        roots = np.roots(np.asarray(quadratic(lengths, [t1, t2, t5])).ravel())
        assert np.min(np.abs(roots - np.tan(t4 / 2))) < 1e-8 * (1 + abs(np.tan(t4 / 2)))
        a1, b1, c1 = _published(*lengths, t1, t2, t5, lib=np)
        printed = np.roots([a1, -b1, c1])          # -b1: undo the printed sign convention of t
        misses += np.min(np.abs(printed - np.tan(t4 / 2))) > 1e-3
    assert misses >= 45


def test_discriminant_says_when_the_chain_can_close(rng):
    """Independent check: E exists iff |F - B| lies between |L3 - L4| and L3 + L4."""
    disagreements_printed, checked = 0, 0
    for _ in range(400):
        lengths = rng.uniform(0.3, 2.0, 5)
        t1, t2, t5 = rng.uniform(-np.pi, np.pi, 3)
        l1, l2, l3, l4, l5 = lengths
        f = l1 * np.array([np.cos(t1), np.sin(t1)]) + l2 * np.array([np.cos(t2), np.sin(t2)])
        distance = np.linalg.norm(f - l5 * np.array([-np.cos(t5), np.sin(t5)]))
        closes = abs(l3 - l4) <= distance <= l3 + l4
        margin = min(abs(distance - abs(l3 - l4)), abs(distance - (l3 + l4)))
        if margin < 1e-6:
            continue
        checked += 1
        assert (float(discriminant(lengths, [t1, t2, t5])) >= 0) == closes
        a1, b1, c1 = _published(*lengths, t1, t2, t5, lib=np)
        disagreements_printed += (b1**2 - 4 * a1 * c1 >= 0) != closes
    assert checked > 350 and disagreements_printed > 0

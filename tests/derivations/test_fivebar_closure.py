"""Wang et al. 2025 eq (7)-(10): the five-bar closure, its half-angle quadratic and discriminant.

Eq (8) as printed is the derived closure. The printed A1 of eq (9) is not: it carries
-2 L1 L4 cos(theta1) - 2 L2 L4 cos(theta2) where the derivation has + (A - A1 = 4 L4 (L1 cos
theta1 + L2 cos theta2)); the printed B1 is -B (the sign of t = tan(theta4/2) flipped, which
alone would be harmless); C1 = C. With the printed A1 the quadratic's roots miss theta4 of a
five-bar that closes, and its discriminant misjudges which crank positions can close.
"""
import numpy as np
import pytest
import sympy as sp

from derivations import fivebar
from tests.published_script import reproduce
from transplanter._generated.fivebar import (
    fivebar_assembly_sine,
    fivebar_closure,
    fivebar_closure_margin,
    fivebar_discriminant,
    fivebar_half_angle_quadratic,
    fivebar_plate_hinges,
    fivebar_pose_closure,
    fivebar_transmission_margin,
    fivebar_triangle_margins,
)
from transplanter.fivebar.linkage import FiveBar
from transplanter.generated import casadi_function
from transplanter.geometry.planar import unit

L = sp.symbols("L1:6", positive=True)
T1, T2, T4, T5 = sp.symbols("theta1 theta2 theta4 theta5", real=True)
quadratic = casadi_function(fivebar_half_angle_quadratic)
discriminant = casadi_function(fivebar_discriminant)
closure = casadi_function(fivebar_closure)


def _published(l1, l2, l3, l4, l5, t1, t2, t5, lib=sp):
    """Eq (9) coefficients as printed in Wang et al. 2025 (the script's transcription)."""
    return reproduce.printed_eq9((l1, l2, l3, l4, l5), (t1, t2, t5), lib)


def test_printed_eq8_is_the_derived_closure():
    printed = (L[0]**2 + L[1]**2 - L[2]**2 + L[3]**2 + L[4]**2 + 2 * L[0] * L[4] * sp.cos(T1 + T5)
               + 2 * L[1] * L[4] * sp.cos(T2 + T5) - 2 * L[3] * L[4] * sp.cos(T4 + T5)
               + 2 * L[0] * L[1] * sp.cos(T1 - T2) - 2 * L[0] * L[3] * sp.cos(T1 - T4)
               - 2 * L[1] * L[3] * sp.cos(T2 - T4))
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
    gap = l1 * unit(t1) + l2 * unit(t2) - l5 * np.array([-np.cos(t5), np.sin(t5)]) - l4 * unit(t4)
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


def test_triangle_margins_are_eq10s_margin_and_the_transmission_margin(rng):
    """The short form the design NLP evaluates (law of cosines in |BF|^2, sine rule) against the margins written
    through eq (8)'s P, Q, R, at lengths and crank angles where the chain closes and where it does not (the
    identity is algebraic: both sides are the same rational function)."""
    triangle = casadi_function(fivebar_triangle_margins)
    closure_margin = casadi_function(fivebar_closure_margin)
    transmission = casadi_function(fivebar_transmission_margin)
    for _ in range(300):
        lengths, crank = rng.uniform(0.3, 2.0, 5), rng.uniform(-np.pi, np.pi, 3)
        short = np.asarray(triangle(lengths, crank)).ravel()
        expected = float(closure_margin(lengths, crank)), float(transmission(lengths, crank))
        assert short == pytest.approx(expected, rel=1e-10, abs=1e-12 * max(1.0, *np.abs(expected)))


def test_position_closure_vanishes_and_assembly_sine_is_the_margin_along_forward_kinematics(rng):
    """The rows the design NLP imposes at a pose (``fivebar_pose_closure``, ``fivebar_assembly_sine``, the plate's
    hinges and the transmission margin) evaluated on the hinges the independent forward kinematics places
    (circle intersections, no closure algebra): the loop closes to rounding, the sine's sign is the assembly
    branch and its square the closure margin, and sin^2(BEF) is the angle at E measured by atan2."""
    hinges = casadi_function(fivebar_plate_hinges)
    residual = casadi_function(fivebar_pose_closure)
    sine = casadi_function(fivebar_assembly_sine)
    transmission = casadi_function(fivebar_transmission_margin)
    triangle = casadi_function(fivebar_triangle_margins)
    checked = 0
    for _ in range(40):
        mech = FiveBar(carrier_length=rng.uniform(40, 80), carrier_angle=rng.uniform(-np.pi, np.pi),
                       rod_length=rng.uniform(150, 250), hinge_b=rng.uniform(-100, 100, 2),
                       receiving_length=rng.uniform(150, 300), e_local=rng.uniform(-60, 60, 2),
                       f_local=rng.uniform(-60, 60, 2), branch=rng.choice([-1.0, 1.0]))
        turns, rho = rng.uniform(0, 2 * np.pi, 5), rng.uniform(-np.pi, np.pi, 5)
        state = mech.forward(turns, rho)
        for k in np.flatnonzero(state["margin"] > 1e-3):
            pose = [*state["p"][k], state["direction"][k]]
            plate = [*mech.e_local, *mech.f_local]
            theta1 = mech.carrier_angle - turns[k]
            e, f = (np.asarray(h).ravel() for h in hinges(pose, plate))
            assert np.allclose(e, state["e"][k], atol=1e-9) and np.allclose(f, state["f"][k], atol=1e-9)
            rows = np.asarray(residual(pose, plate, mech.hinge_b, [mech.carrier_length, mech.rod_length,
                                                                   mech.receiving_length],
                                       [theta1, theta1 + rho[k]])).ravel()
            assert np.abs(rows).max() < 1e-8
            value = float(sine(pose, plate, mech.hinge_b, mech.receiving_length))
            assert np.sign(value) == mech.branch and value**2 == pytest.approx(state["margin"][k], rel=1e-9)
            b = mech.hinge_b
            lengths = [mech.carrier_length, mech.rod_length, mech.link_length, mech.receiving_length, np.hypot(*b)]
            u, v = b - e, f - e
            at_e = np.arctan2(abs(u[0] * v[1] - u[1] * v[0]), np.dot(u, v))
            crank = [theta1, theta1 + rho[k], np.arctan2(b[1], -b[0])]
            assert float(transmission(lengths, crank)) == pytest.approx(np.sin(at_e) ** 2, rel=1e-9, abs=1e-12)
            assert np.asarray(triangle(lengths, crank)).ravel() == \
                pytest.approx([state["margin"][k], np.sin(at_e) ** 2], rel=1e-9, abs=1e-12)
            checked += 1
    assert checked > 50

"""The variable involute of the cusp-pitch-curve paper (eq 1-6): the closed form re-derived, the pinion cutter,
and the shaper path measured against the closed form."""
import numpy as np
import pytest
import sympy as sp

from derivations import cusp as derivation
from transplanter._generated import cusp
from transplanter.gears.pair import arc_length, design_pair
from transplanter.gears.pinion_cutter import shaper_cutter_radii
from transplanter.gears.pitch_curves import ellipse
from transplanter.gears.swept_teeth import BIN_MODULES, shaper_profile
from transplanter.gears.teeth import driver_table
from transplanter.gears.variable_involute import involute_deviation
from transplanter.generated import numpy_twin
from transplanter.geometry.turn_quadrature import panels

reach = numpy_twin(cusp.shaper_reach)
variable_involute = numpy_twin(cusp.variable_involute)


@pytest.mark.parametrize("side", [1, -1])
def test_any_pinion_cutter_generates_the_racks_flank(side):
    """The flank point a cutter of pitch radius r_j generates (its involute's normal through the contact) is the rack
    formula of rack_teeth, free of r_j; it is the pitch point when nothing has rolled."""
    alpha, rolled = sp.symbols("alpha delta", real=True)
    radius = sp.Symbol("r_j", positive=True)
    point, _, residual = derivation.shaper_contact(alpha, rolled, radius, side)
    rack = sp.Matrix([rolled * sp.cos(alpha) ** 2, -side * rolled * sp.sin(alpha) * sp.cos(alpha)])
    assert sp.simplify(point - rack) == sp.zeros(2, 1)
    assert radius not in point.free_symbols and residual == 0


@pytest.mark.parametrize("side", [1, -1])
def test_the_printed_steps_of_eq_5_hold(side):
    """|S I| = sqrt(r_b^2 + SN^2) with SN = r_b (tan(alpha) + phi_s), and the angle S I M2 = alpha_s - alpha with
    tan(alpha_s) = tan(alpha) + phi_s, phi_s = side delta / r_j (the slip coefficient f(mu) = 1)."""
    alpha, rolled, radius = sp.Rational(7, 20), sp.Rational(-13, 10), 11
    point, _, _ = derivation.shaper_contact(alpha, rolled, radius, side)
    base, phi_s = radius * sp.cos(alpha), side * rolled / radius
    to_s, to_m2 = point - sp.Matrix([0, radius]), sp.Matrix([0, -radius])
    expected = sp.sqrt(base ** 2 + (base * (sp.tan(alpha) + phi_s)) ** 2)
    assert float(to_s.norm()) == pytest.approx(float(expected), rel=1e-14)
    angle = sp.acos(to_s.dot(to_m2) / (to_s.norm() * radius))
    assert float(angle) == pytest.approx(float(abs(sp.atan(sp.tan(alpha) + phi_s) - alpha)), rel=1e-12)


@pytest.mark.parametrize("side", [1, -1])
def test_on_a_circle_the_variable_involute_is_the_involute_of_its_base_circle(side):
    """Pitch circle R, one flank (its pitch point fixed at s_f) generated over 3 mm of roll each way: every point's
    polar angle differs from the flank's by the involute function inv(t) = t - atan(t), t = sqrt(rho^2 / r_b^2 - 1),
    with r_b = R cos(alpha): the flank is the involute of the base circle, unwinding against the tooth's side."""
    radius, alpha, pitch_arc = 24.0, np.radians(20), 5.0
    rolled = np.linspace(-3.0, 3.0, 41)
    psi = (pitch_arc - rolled) / radius                      # the contact on the circle (counterclockwise)
    normal = np.c_[np.cos(psi), np.sin(psi)]
    tangent = np.c_[-np.sin(psi), np.cos(psi)]
    (along, out), = variable_involute([np.full_like(rolled, alpha)], [rolled], [np.full_like(rolled, side)])
    points = radius * normal + along[:, None] * tangent + out[:, None] * normal
    rho = np.hypot(*points.T)
    roll = np.sqrt(rho ** 2 / (radius * np.cos(alpha)) ** 2 - 1)
    polar = np.arctan2(points[:, 1], points[:, 0]) - side * (roll - np.arctan(roll))
    assert rho.min() < radius < rho.max() and np.ptp(polar) < 1e-14
    assert np.ptp(np.arctan2(points[:, 1], points[:, 0]) + side * (roll - np.arctan(roll))) > 0.05   # not the mirror


@pytest.mark.parametrize("teeth,alpha_deg", [(16, 20.0), (50, 20.0), (12, 25.0)])
def test_shaper_reach_ends_where_the_contact_meets_the_cutters_lowest_and_tip_circles(teeth, alpha_deg):
    alpha, module = np.radians(alpha_deg), 2.0
    radius, tip, lowest = shaper_cutter_radii(module, alpha, teeth)
    (low, high), = reach([alpha], [radius], [tip], [lowest])
    for q, circle in ((low, tip), (high, lowest)):
        side = 1.0
        contact = np.array([-side * q * np.cos(alpha) ** 2, q * np.sin(alpha) * np.cos(alpha)])  # delta = -side q
        assert np.hypot(contact[0], contact[1] - radius) == pytest.approx(circle, rel=1e-12)
    assert low < 0 < high


@pytest.mark.parametrize("alpha_deg", [20.0, 30.0, 33.0])
def test_shaper_reach_at_the_base_circle_is_exact(alpha_deg):
    """A cutter whose involute starts at its base circle (lowest radius r_j cos(alpha), 16 teeth at 30 deg): the reach
    ends at q = r_j tan(alpha), with no square root of a rounding below zero (a NaN and a numpy warning before)."""
    alpha, module = np.radians(alpha_deg), 2.0
    radius, tip, _ = shaper_cutter_radii(module, alpha, 16)
    (_, high), = reach([alpha], [radius], [tip], [radius * np.cos(alpha)])
    assert high == pytest.approx(radius * np.tan(alpha), rel=1e-15)


def _ellipse_design(module=2.0, teeth=24):
    curve = ellipse(30.0, 0.2)
    return design_pair(curve.scaled(np.pi * module * teeth / arc_length(curve, panels(curve.breaks))[-1]), 1)


@pytest.mark.parametrize("cutter_teeth", [16, 40])
def test_shaper_path_cuts_the_closed_form_whatever_the_cutters_size(cutter_teeth):
    """On an ellipse, shapers of 16 and 40 teeth both cut the closed form within one bin of the envelope (each bin,
    0.002 module of pitch arc, keeps the lowest height over its width, so a sloped flank moves by up to half a bin),
    where their involutes generate it; the closed form displaced by 0.01 module along the pitch curve is not."""
    module, alpha, teeth = 2.0, np.radians(20), 24
    design = _ellipse_design(module, teeth)
    table = driver_table(design)
    pitch = np.pi * module
    spaces = pitch / 2 + pitch * np.arange(teeth)             # shaper_profile's tooth k is centred at k p
    flanks = np.r_[spaces - pitch / 4, spaces + pitch / 4]
    sides = np.r_[-np.ones(teeth), np.ones(teeth)]             # a space's low end is a tooth's high-arc flank
    outline = shaper_profile(table, module, alpha, cutter_teeth)
    found = involute_deviation(table, outline, flanks, sides, np.ones(2 * teeth, bool), np.empty(0), module, alpha,
                               cutter_teeth)
    assert found.flanks_compared == 2 * teeth and found.points_compared > 30 * 2 * teeth
    assert found.largest_mm < BIN_MODULES * module
    shifted = involute_deviation(table, outline, flanks + 0.01 * module, sides, np.ones(2 * teeth, bool), np.empty(0),
                                 module, alpha, cutter_teeth)
    assert shifted.largest_mm > 0.005 * module

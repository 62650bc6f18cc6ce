"""Composite teeth on a pitch curve with corners (seed 004 sec 2-3): cycloid arches, layout, checks."""
import numpy as np
import pytest
import sympy as sp

from derivations import cusp as derivation
from transplanter.errors import InfeasibleError
from transplanter.gears import parse_problem, synthesize
from transplanter.gears.composite_teeth import _check_layout, carved_mate, layout
from transplanter.gears.mesh_check import check_mesh
from transplanter.gears.pair import arc_length, design_pair
from transplanter.gears.pitch_curves import ellipse
from transplanter.gears.swept_teeth import shaper_profile
from transplanter.gears.teeth import driver_table
from transplanter.generated import numpy_twin
from transplanter.geometry.turn_quadrature import panels

trace = numpy_twin("cusp", "cycloid_trace")
incomplete = numpy_twin("cusp", "incomplete_cycloid")


def test_rolling_circle_on_a_line_is_the_cycloid():
    r, theta = sp.symbols("r theta", positive=True)
    x, y = derivation.cycloid_trace(r * theta, 0, 0, r, theta, 1)
    # tangent angle 0 on a counterclockwise curve: outward normal -y, so the cycloid hangs below the x axis
    assert sp.simplify(x - (r * theta - r * sp.sin(theta))) == 0
    assert sp.simplify(y + (r - r * sp.cos(theta))) == 0


def test_rolling_circle_on_a_circle_is_the_epicycloid():
    """Base circle R (counterclockwise, outward normal radial) and rolling circle r: the generated trace is the
    epicycloid (R + r) e(t) - r e((R + r) t / r) that starts at (R, 0)."""
    big, small = 7.0, 1.3
    t = np.linspace(0, 1.2, 50)
    base = big * np.c_[np.cos(t), np.sin(t)]
    (x, y), = trace(base.T, [t + np.pi / 2], [np.full_like(t, small)], [big * t / small], [np.ones_like(t)])
    expected = (big + small) * np.c_[np.cos(t), np.sin(t)] - small * np.c_[np.cos((big + small) * t / small),
                                                                           np.sin((big + small) * t / small)]
    assert np.abs(np.c_[x, y] - expected).max() < 1e-12


@pytest.mark.parametrize("alpha_deg,end_deg", [(20.0, 120.0), (0.0, 180.0), (14.5, 100.0)])
def test_incomplete_arch_starts_on_the_pitch_line_leaning_alpha_and_ends_over_the_corner(alpha_deg, end_deg):
    alpha, end, zone = np.radians(alpha_deg), np.radians(end_deg), 3.0
    theta0, radius, depth, top = (float(v[0]) for v in incomplete([alpha], [zone], [end]))
    corner = 10.0
    theta = np.linspace(theta0, end, 2001)
    contact = corner - radius * (end - theta)
    # pitch line: the x axis run towards +x (tangent angle 0, outward normal -y); the base lies depth inside it
    (x, y), = trace(np.c_[contact, np.full_like(theta, depth)].T, [np.zeros_like(theta)],
                    [np.full_like(theta, radius)], [theta], [np.ones_like(theta)])
    height = -y
    assert abs(height[0]) < 1e-12 and x[0] == pytest.approx(corner - zone, abs=1e-12)   # starts at A on the pitch line
    lean = np.degrees(np.arctan2(abs(x[1] - x[0]), abs(height[1] - height[0])))
    assert lean == pytest.approx(alpha_deg, abs=0.05)                                    # leans alpha off the normal
    assert height[-1] == pytest.approx(top, abs=1e-12)
    assert x[-1] == pytest.approx(corner - radius * np.sin(end), abs=1e-12)               # its circle touches the corner
    if alpha_deg == 0:
        assert radius == pytest.approx(zone / end, rel=1e-12)         # seed 004 eq 7: r_gy = S / (2 pi n), theta1 = 2 pi n


def test_seed_004_elliptic_rolling_starts_along_the_pitch_curve():
    a1, b1 = sp.symbols("a1 b1", positive=True)
    along, normal = derivation.paper_variable_cycloid_start(a1, b1)
    assert sp.simplify(along - (1 - 1 / a1)) == 0 and normal == 0
    assert along.subs(a1, 1) == 0 and along.subs(a1, sp.Rational(3, 2)) != 0


def test_layout_and_the_thickness_band():
    pitch = np.pi * 2.0
    plan = layout(np.array([0.0, 3.3 * pitch]), 20 * pitch, pitch)
    assert list(plan.between) == [2, 15] and np.allclose(plan.thickness_ratios, 1.0)
    total = plan.between.sum() * pitch + len(plan.corners) * pitch / 2 + (plan.before + plan.after).sum()
    assert total == pytest.approx(20 * pitch)
    skewed = layout(np.array([0.0, 2.0 * pitch, 4.5 * pitch]), 20 * pitch, pitch)
    assert skewed.thickness_ratios.max() == pytest.approx(1.25)
    with pytest.raises(InfeasibleError) as error:
        _check_layout(skewed, 20, [(100.0, 100.0)] * 3, "f.toml")
    message = str(error.value)
    assert message.startswith("f.toml: pair.teeth = 20: the tooth on the corner") and "tooth counts that fit" in message
    with pytest.raises(InfeasibleError, match="cusp zone of .* wider than the segment"):
        _check_layout(plan, 20, [(1.0, 100.0), (100.0, 100.0)], "f.toml")


def test_carved_mate_is_conjugate_on_an_ellipse_pair():
    """A shaper-cut elliptic driver and its mate carved as polygons mesh through a whole turn."""
    module, teeth = 2.0, 24
    curve = ellipse(30.0, 0.2)
    curve = curve.scaled(np.pi * module * teeth / arc_length(curve, panels(curve.breaks))[-1])
    design = design_pair(curve, 1)
    driver = shaper_profile(driver_table(design), module, np.radians(20), 16)
    mesh = check_mesh(design, (driver, carved_mate(design, driver, module)), module)
    assert mesh.passed, mesh.failures


@pytest.fixture(scope="module")
def example():
    return synthesize(parse_problem({
        "driver": {"family": "composite", "segments": [
            {"kind": "ellipse", "phi_deg": [-150, 150], "semi_major_axis": 30.0, "eccentricity": 0.3},
            {"kind": "line", "phi_deg": [150, 210]}]},
        "pair": {"module": 2.0, "teeth": 30}}))


def test_composite_teeth_of_the_ellipse_and_chord(example):
    report = example.to_json()
    assert report["self_intersections"] == [0, 0]
    assert report["tooth_counts_built"] == [29, 29]              # 27 regular teeth and 2 corner teeth, each a pitch thick
    for tooth in report["corner_teeth"]:
        assert tooth["thickness_pitches"] == pytest.approx(1.0)
        assert max(tooth["joint_kinks_deg"]) < 2.0              # the arch leans alpha where it meets the involute
        assert max(tooth["joint_gaps_mm"]) < 0.025 * 2.0
        for low, high in tooth["arch_pressure_angles_deg"]:
            assert low == pytest.approx(20.0, abs=1.0) and high == pytest.approx(60.0, abs=0.5)
    assert report["mesh_check"]["max_overlap_mm"] < 0.005 * 2.0
    assert set(report) >= {"cusps", "contact_ratio_min", "contact_ratio_where", "mesh_check"}


def test_teeth_on_the_straight_segment_are_a_racks(example):
    """The shaper rolling on the chord cuts what it cuts on a rack: straight flanks leaning alpha off the normal."""
    d = example.design
    outline = example.teeth.outlines[0]
    chord_start, chord_end = (d.driver.evaluate(np.radians([a]))[0][0] * np.array([np.cos(np.radians(a)),
                                                                                np.sin(np.radians(a))])
                              for a in (150.0, 210.0))
    along = (chord_end - chord_start) / np.linalg.norm(chord_end - chord_start)
    outward = np.array([along[1], -along[0]])
    t = (outline - chord_start) @ along
    h = (outline - chord_start) @ outward
    length = np.linalg.norm(chord_end - chord_start)
    middle = np.flatnonzero((t > 0.3 * length) & (t < 0.7 * length) & (np.abs(h) < 0.5 * 2.0))   # +-0.5 m
    runs = np.split(middle, np.flatnonzero(np.diff(middle) > 1) + 1)
    flanks = [run for run in runs if len(run) > 50]
    assert len(flanks) >= 2
    for run in flanks:                     # each flank: a straight line leaning alpha = 20 deg off the normal
        slope, offset = np.polyfit(h[run], t[run], 1)
        assert np.degrees(np.arctan(abs(slope))) == pytest.approx(20.0, abs=0.1)
        # the shaper's outline has a point per 0.002-module bin: 0.0055 module of height at 20 deg; twice that
        assert np.abs(t[run] - (slope * h[run] + offset)).max() < 2 * 0.002 / np.tan(np.radians(20)) * 2.0

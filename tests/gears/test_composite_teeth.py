"""Composite teeth on a pitch curve with corners (the cusp-pitch-curve paper, sections 2-3): cycloid arches,
layout, checks."""
import dataclasses
import types

import numpy as np
import pytest
import sympy as sp

from derivations import cusp as derivation
from tests.api.test_problem_classes import assert_pickles_to_the_same_report
from transplanter._generated.cusp import cycloid_trace, incomplete_cycloid
from transplanter.errors import InfeasibleError
from transplanter.gears import parse_problem, synthesize
from transplanter.gears.composite_teeth import (
    CORNER_PRESSURE_TRIALS_DEG,
    _check_arches_apart,
    _check_layout,
    _first_that_passes,
    carved_mate,
    layout,
)
from transplanter.gears.mesh_check import ERROR_MODULES, check_mesh
from transplanter.gears.pair import arc_length, arc_to_angle, design_pair
from transplanter.gears.pitch_curves import ellipse
from transplanter.gears.swept_teeth import BIN_MODULES, shaper_profile
from transplanter.gears.teeth import driver_table
from transplanter.gears.tooth_contact import SAMPLES_PER_PITCH, measure_contact_ratio
from transplanter.generated import numpy_twin
from transplanter.geometry.turn_quadrature import panels

trace = numpy_twin(cycloid_trace)
incomplete = numpy_twin(incomplete_cycloid)


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


@pytest.mark.parametrize("alpha_deg,corner_deg", [(20.0, 60.0), (0.0, 180.0), (14.5, 40.0)])
def test_incomplete_arch_goes_on_from_a_straight_flank_leaning_alpha_and_rolls_onto_the_corner(alpha_deg, corner_deg):
    """On a pitch line (the x axis run towards +x, outward normal -y) with A at x = 0: the arch's first point lies on
    the straight flank from A leaning alpha and leans alpha itself; its circle touches the corner, a zone after A,
    when it has turned theta_J; the generated heights are the trace's."""
    alpha, corner_angle, zone = np.radians(alpha_deg), np.radians(corner_deg), 3.0
    theta0, radius, cusp, joint, over_corner = (float(v[0]) for v in incomplete([alpha], [zone], [corner_angle]))
    theta = np.linspace(theta0, corner_angle, 2001)
    contact = cusp + radius * theta                                   # the circle rolls on the pitch line itself
    (x, y), = trace(np.c_[contact, np.zeros_like(theta)].T, [np.zeros_like(theta)], [np.full_like(theta, radius)],
                    [theta], [np.ones_like(theta)])
    height = -y
    assert theta0 == pytest.approx(2 * alpha, abs=1e-12)
    assert height[0] == pytest.approx(joint, abs=1e-12) and x[0] == pytest.approx(joint * np.tan(alpha), abs=1e-12)
    lean = np.degrees(np.arctan2(x[1] - x[0], height[1] - height[0]))
    assert lean == pytest.approx(alpha_deg, abs=0.05)
    assert contact[-1] == pytest.approx(zone, abs=1e-12) and height[-1] == pytest.approx(over_corner, abs=1e-12)
    # the normal of the arch passes through the rolling contact: conjugate to its envelope
    tangent = np.gradient(np.c_[x, height], theta, axis=0)[1:-1]
    to_contact = np.c_[contact - x, -height][1:-1]
    assert np.abs(np.sum(tangent * to_contact, axis=1)).max() < 1e-4 * radius ** 2
    if alpha_deg == 0:
        # the rolling circle of the cusp-pitch-curve paper's eq 7: r_gy = S / (2 pi n)
        assert radius == pytest.approx(zone / corner_angle, rel=1e-12)


def test_cusp_pitch_curve_papers_elliptic_rolling_starts_along_the_pitch_curve():
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
    assert message.startswith("f.toml: pair.teeth = 20: the tooth on the corner")
    assert "tooth counts that keep every corner tooth in the band" in message
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
    # 27 regular teeth and 2 corner teeth, each a pitch thick
    assert report["tooth_counts_built"] == [29, 29]
    for tooth in report["corner_teeth"]:
        assert tooth["thickness_pitches"] == pytest.approx(1.0)
        assert max(tooth["joint_kinks_deg"]) < 3.0              # the straight flank leans alpha as the shaper's does
        assert max(tooth["joint_gaps_mm"]) < 0.01 * 2.0       # within the mesh check's backlash
        # alpha at the joint; the arch reaches the corner and leaves the tip band as its circle pivots there,
        # at the corner's pressure angle (22 deg, the first one tried)
        for low, high in tooth["arch_pressure_angles_deg"]:
            assert low == pytest.approx(20.0, abs=1e-9) and high == pytest.approx(22.0, abs=1e-9)
    assert report["corner_pressure_angle_deg"] == 22.0
    assert report["corner_pressure_trials"] == [
        {"corner_pressure_angle_deg": 22.0, "passed": True, "failures": [],
         "transmission_error_mm": report["mesh_check"]["transmission_error_mm"]}]
    assert report["mesh_check"]["passed"] and report["mesh_check"]["max_overlap_mm"] < 0.005 * 2.0
    assert report["contact_ratio_min"] >= 1.0 and not any(report["contact_lost_at_deg"].values())
    # every space's two flanks against the closed-form variable involute (the corner teeth's above the pitch curve
    # are cycloid arches), within one bin of the shaper's envelope
    involute = report["variable_involute"]
    assert involute["flanks_compared"] == 2 * 29 and involute["largest_mm"] < BIN_MODULES * 2.0
    assert example.passed
    assert set(report) >= {"cusps", "contact_ratio_min", "contact_ratio_where", "mesh_check"}
    markdown = example.to_markdown()                            # the report says what the checks found
    assert (f"corner pressure angle 22 deg (tried: 22 deg passed (transmission error "
            f"{report['mesh_check']['transmission_error_mm']:.4f} mm))") in markdown
    assert f"transmission error {report['mesh_check']['transmission_error_mm']:.4f} mm" in markdown
    assert f"contact ratio at least {report['contact_ratio_min']:.3f}" in markdown
    assert markdown.count("- corner tooth at pitch arc") == 2 and "positions without contact: none" in markdown


def test_the_composite_pair_pickles(example):
    """The example (the driver and pair of examples/gear_cusp_composite.toml) goes through pickle as every job's
    result does (tests/api/test_problem_classes.py): its corner teeth, arches and trials too."""
    assert_pickles_to_the_same_report(example)


def test_arch_normals_pass_through_the_rolling_contact_on_the_pitch_curve(example):
    """Each corner arch, on the example's ellipse arc and chord: the normal at every rolled point passes through
    its rolling contact on the pitch curve, and while the circle pivots, through the corner."""
    design = example.design
    for tooth in example.teeth.corner_teeth:
        for arch in tooth.arches:
            points = arch.points[len(arch.points) - len(arch.theta):]
            phi = arc_to_angle(design, arch.contact_arc)
            contact = design.driver.evaluate(phi)[0][:, None] * np.c_[np.cos(phi), np.sin(phi)]
            tangent = np.gradient(points, axis=0)
            tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
            off_normal = np.abs(np.sum(tangent * (contact - points), axis=1))
            # points whose two neighbours are an even step of theta away (the central difference is second order
            # there; next to the pivot the steps change and the difference is not a tangent)
            step = np.diff(arch.theta)
            even = np.r_[False, np.isclose(step[:-1], step[1:], rtol=1e-6) & (step[1:] > 0), False]
            # 1.3e-5 mm measured, the central difference's own error; a linear lookup of the contact's angle against
            # arc length put it at 0.016 mm, 1200 times more
            assert off_normal[even].max() < 5e-5 * 2.0
            pivot = np.flatnonzero(np.diff(arch.theta) == 0)[1:-1]
            assert np.allclose(np.linalg.norm(points[pivot] - contact[pivot], axis=1),
                               2 * arch.radius * np.sin(arch.corner_angle / 2), rtol=1e-9)


def test_without_a_corner_pressure_angle_the_first_that_passes_is_kept():
    """Corners turning 31 deg (the ellipse from -140 to 140 deg): at 22 deg the transmission error peaks just before
    each corner beyond the tolerance, so 26 deg is tried next and passes; the report keeps both trials."""
    result = synthesize(parse_problem({
        "driver": {"family": "composite", "segments": [
            {"kind": "ellipse", "phi_deg": [-140, 140], "semi_major_axis": 30.0, "eccentricity": 0.3},
            {"kind": "line", "phi_deg": [140, 220]}]},
        "pair": {"module": 2.0, "teeth": 30}}))
    report = result.to_json()
    first, second = report["corner_pressure_trials"]
    assert first["corner_pressure_angle_deg"] == 22.0 and not first["passed"]
    assert any(failure.startswith("transmission error") for failure in first["failures"])
    assert first["transmission_error_mm"] > ERROR_MODULES * 2.0
    assert second == {"corner_pressure_angle_deg": 26.0, "passed": True, "failures": [],
                      "transmission_error_mm": report["mesh_check"]["transmission_error_mm"]}
    assert "22 deg failed (transmission error" in result.to_markdown()
    assert report["corner_pressure_angle_deg"] == 26.0 and result.passed


def test_corner_pressure_angle_that_stops_the_arch_short_of_the_corner_is_refused():
    with pytest.raises(InfeasibleError,
                       match=r"pair.corner_pressure_angle_deg = 60: .* above the tip .* use at most 43\.\d deg"):
        synthesize(parse_problem({
            "driver": {"family": "composite", "segments": [
                {"kind": "ellipse", "phi_deg": [-150, 150], "semi_major_axis": 30.0, "eccentricity": 0.3},
                {"kind": "line", "phi_deg": [150, 210]}]},
            "pair": {"module": 2.0, "teeth": 30, "corner_pressure_angle_deg": 60.0}}))


def test_cycloid_flanks_that_cross_are_refused():
    """Two rising flanks that cross below the tip (constructed: the left leans over the right) are refused with the
    field, its value and the angles that fit; flanks apart pass."""
    left, right = np.array([[0.0, 0.0], [3.0, 2.0]]), np.array([[2.0, 0.0], [1.0, 2.0]])
    alpha, tip = np.radians(20), 2.0
    with pytest.raises(InfeasibleError, match=r"f.toml: pair.corner_pressure_angle_deg = 25: the two cycloid flanks "
                                              r".* cross below its tip .* use at most \d+\.\d deg, or use more teeth"):
        _check_arches_apart([left, right], (3.0, 3.0), 3.0, alpha, np.radians(25), tip, 80.0, "f.toml")
    apart = np.array([[4.0, 0.0], [3.5, 2.0]])
    _check_arches_apart([left, apart], (3.0, 3.0), 3.0, alpha, np.radians(25), tip, 80.0, "f.toml")


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


@pytest.mark.parametrize("turn_mm", [0.1, -0.1])
def test_contact_ratio_sees_a_driven_gear_turned_off_its_mesh(example, turn_mm):
    """Negative control of the contact measurement: the driven outline turned about its centre by 0.1 mm of pitch arc
    (five times the touching distance) leaves one flank side touching nowhere and the other touching everywhere
    (where it cuts in)."""
    design, (driver, driven), module = example.design, example.teeth.outlines, 2.0
    angle = turn_mm / np.mean(np.linalg.norm(design.points[1], axis=1))
    turned = driven @ np.array([[np.cos(angle), np.sin(angle)], [-np.sin(angle), np.cos(angle)]])
    contact = measure_contact_ratio(design, (driver, turned), module,
                                    example.teeth.plan.space_centers(design.perimeters[0]))
    positions = len(np.arange(0.0, design.perimeters[0], np.pi * module / SAMPLES_PER_PITCH))
    lost = sorted(len(angles) for angles in contact.uncovered_deg)
    assert lost == [0, positions]
    untouched = int(np.argmax([len(angles) for angles in contact.uncovered_deg]))
    assert np.all(contact.ratios[untouched] == 0)


@dataclasses.dataclass
class _Trial:
    """What _first_that_passes reads of a pair: its failures, transmission error and trials."""
    degrees: float
    failures: list
    mesh: types.SimpleNamespace
    trials: tuple = ()

    @property
    def passed(self):
        return not self.failures


def _trying(outcomes: dict):
    """A pair_at whose outcome per corner pressure angle (deg) is a transmission error (mm, failing when above
    0.01) or a refusal (None)."""
    def pair_at(angle):
        degrees = round(float(np.degrees(angle)), 9)
        error = outcomes[degrees]
        if error is None:
            raise InfeasibleError(f"<dict>: pair.corner_pressure_angle_deg = {degrees:g}: refused")
        return _Trial(degrees, ["transmission error"] if error > 0.01 else [],
                      types.SimpleNamespace(max_transmission_error_mm=error))
    return pair_at


def test_when_no_corner_pressure_angle_passes_the_smallest_transmission_error_is_kept():
    outcomes = {22.0: 0.05, 26.0: 0.03, 30.0: 0.04, 34.0: None, 38.0: None}
    kept = _first_that_passes(_trying(outcomes), CORNER_PRESSURE_TRIALS_DEG)
    assert kept.degrees == 26.0 and not kept.passed
    assert [t.degrees for t in kept.trials] == list(CORNER_PRESSURE_TRIALS_DEG)
    assert [t.refused is not None for t in kept.trials] == [False, False, False, True, True]


def test_the_first_refusal_is_raised_when_every_angle_is_refused():
    with pytest.raises(InfeasibleError, match="corner_pressure_angle_deg = 22: refused"):
        _first_that_passes(_trying(dict.fromkeys(CORNER_PRESSURE_TRIALS_DEG)), CORNER_PRESSURE_TRIALS_DEG)


def test_trials_stop_at_the_first_pair_that_passes_after_a_refusal():
    kept = _first_that_passes(_trying({22.0: None, 26.0: 0.002, 30.0: 0.001, 34.0: 0.0, 38.0: 0.0}),
                              CORNER_PRESSURE_TRIALS_DEG)
    assert kept.degrees == 26.0 and kept.passed and len(kept.trials) == 2


def test_only_corner_pressure_angles_above_the_pressure_angle_are_tried():
    """The arch starts leaning alpha, so angles at or below it are not tried (they made an empty arch before)."""
    result = synthesize(parse_problem({
        "driver": {"family": "composite", "segments": [
            {"kind": "ellipse", "phi_deg": [-150, 150], "semi_major_axis": 30.0, "eccentricity": 0.3},
            {"kind": "line", "phi_deg": [150, 210]}]},
        "pair": {"module": 2.0, "teeth": 30, "pressure_angle_deg": 35.0}}))
    assert [t["corner_pressure_angle_deg"] for t in result.to_json()["corner_pressure_trials"]] == [38.0]


def test_a_tooth_outline_that_crosses_itself_at_a_square_corner_is_refused():
    """Four lines 20 mm from the centre: 90-deg corners, on which the corner tooth runs into its neighbours."""
    sides = [{"kind": "line", "phi_deg": [a - 45.0, a + 45.0], "distance": 20.0, "normal_deg": a}
             for a in (0.0, 90.0, 180.0, 270.0)]
    problem = parse_problem({"driver": {"family": "composite", "segments": sides},
                             "pair": {"module": 2.0, "teeth": 30, "corner_pressure_angle_deg": 22.0}}, "f.toml")
    with pytest.raises(InfeasibleError, match=r"f.toml: pair.corner_pressure_angle_deg = 22: "
                                              r"the driver's tooth outline crosses itself at .* "
                                              r"which turns the tangent by 90.0 deg"):
        synthesize(problem)

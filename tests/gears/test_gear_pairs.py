"""Gear pairs against closed forms derived here, against the onion-transplanter paper, and by independent checks."""
import functools

import numpy as np
import pytest
import shapely
import sympy as sp
from scipy.spatial import cKDTree
from shapely import affinity

from derivations import gears as derivation
from transplanter._generated.gears import (
    ellipse_center_distance,
    limacon_center_distance,
    limacon_driven_convexity,
    limacon_driver_convexity,
)
from transplanter.errors import InfeasibleError
from transplanter.gears.mesh_check import ERROR_MODULES, check_mesh
from transplanter.gears.pair import design_pair, driven_angle
from transplanter.gears.pinion_cutter import shaper_cutter, shaper_cutter_radii
from transplanter.gears.pitch_curves import denatured_ellipse, denatured_limacon, denatured_partner, ellipse, limacon
from transplanter.gears.rack_teeth import _flank, pitch_table, rack_profile
from transplanter.gears.swept_teeth import mate_profile, shaper_profile
from transplanter.gears.teeth import driven_table, generate_teeth
from transplanter.generated import casadi_function, numpy_twin
from transplanter.geometry.poses import rotate_about
from transplanter.geometry.turn_quadrature import PIECE_PANELS

ellipse_center = casadi_function(ellipse_center_distance)
limacon_center = casadi_function(limacon_center_distance)


@pytest.mark.parametrize("e", [0.1, 0.3, 0.5])
def test_focal_ellipse_pair(e):
    """Center distance 2a, ratio from (1-e)/(1+e) to (1+e)/(1-e), phi2 = 2 atan((1+e)/(1-e) tan(phi1/2))."""
    d = design_pair(ellipse(25.0, e), 1)
    assert d.center_distance == pytest.approx(50.0, rel=1e-13)
    assert d.ratio.min() == pytest.approx((1 - e) / (1 + e), rel=1e-12)
    assert d.ratio.max() == pytest.approx((1 + e) / (1 - e), rel=1e-12)
    closed = np.unwrap(2 * np.arctan((1 + e) / (1 - e) * np.tan(d.phi1 / 2)))
    assert np.abs(closed - d.phi2).max() < 1e-12
    assert abs(d.closure_error) < 1e-10 and d.rolling_mismatch_mm < 1e-9


@pytest.mark.parametrize("order,driven", [(2, 2), (2, 3), (3, 2), (3, 4), (1, 2)])
def test_higher_order_ellipse_center_distance(order, driven):
    d = design_pair(ellipse(40.0, 0.2, order), driven)
    assert d.center_distance == pytest.approx(float(ellipse_center(40.0, 0.2, driven / order)), rel=1e-12)
    assert abs(d.closure_error) < 1e-10


@pytest.mark.parametrize("driven", [1, 2, 3])
def test_limacon_center_distance(driven):
    d = design_pair(limacon(50.0, 9.0), driven)
    assert d.center_distance == pytest.approx(float(limacon_center(50.0, 9.0, driven)), rel=1e-12)


def test_closed_forms_satisfy_their_closure_equations():
    """The derived roots solve the quadratics they come from (symbolic), and lie beyond the largest radius."""
    a_axis, e, q, b, c = sp.symbols("A e q b c", positive=True)
    root = derivation.ellipse_center_distance_expr(a_axis, e, q)
    p = a_axis * (1 - e**2)
    assert sp.simplify((root - p) ** 2 - root**2 * e**2 - (p * q) ** 2) == 0
    root = derivation.limacon_center_distance_expr(b, c, q)
    assert sp.simplify((1 + 1 / q) ** 2 * ((root - b) ** 2 - c**2) - root**2) == 0


def test_driver_convexity_criterion_is_the_onion_transplanter_papers_eq9():
    """Derived driver convexity at cos(m phi) = -1 is exactly eq (9); it is the minimum over the curve for
    k < 1 and m >= 1, and its sign matches the curvature of the actual curve."""
    k, m, c = sp.symbols("k m c", real=True)
    derived = derivation.limacon_driver_convexity(k, m, c)
    published = (1 - (m**2 + 1) * k) * (1 - k)
    assert sp.expand(derived.subs(c, -1) - published) == 0
    convexity = numpy_twin(limacon_driver_convexity)
    cosine = np.linspace(-1, 1, 401)
    for kk, mm in [(0.1, 1.0), (0.3, 1.5), (0.45, 1.2), (0.2, 2.5), (0.05, 3.0)]:
        values = convexity([kk], [mm], [cosine])[0][0]
        assert values.argmin() == 0
        curve = design_pair(denatured_limacon(1.0, kk, mm, denatured_partner(mm)), 1)
        first_half = curve.phi1 <= np.pi / mm
        assert (curve.convexity[0][first_half] > 0).all() == (values.min() > 0)


def _turns_one_way(points):
    """Convexity read off a closed point set: every corner turns the same way."""
    edges = np.diff(np.r_[points, points[1:2]], axis=0)
    turns = edges[:-1, 0] * edges[1:, 1] - edges[:-1, 1] * edges[1:, 0]
    return bool((turns > 0).all() or (turns < 0).all())


def test_driven_convexity_criterion_of_the_onion_transplanter_papers_eq10_disagrees():
    """Eq (10) has no center distance in it, but the driven curve's convexity depends on it.

    For k = 0.5 and m11 = 2.5 (m12 = 0.625 by eq 2), eq (10) for m11 gives
    (6.25 + 1) 0.25 + (2 - 6.25) 0.5 - 6.25 0.125 + 1 = -0.09375 < 0 (concave), while the derived
    condition and the driven curve's own points (every corner turning one way) say convex.
    """
    k, m11 = 0.5, 2.5
    m12 = denatured_partner(m11)
    published = (m11**2 + 1) * k**2 + (2 - m11**2) * k - m11**2 * k**3 + 1
    assert published == pytest.approx(-0.09375)
    d = design_pair(denatured_limacon(1.0, k, m11, m12), 1)
    assert _turns_one_way(d.points[1][:-1])
    derived = numpy_twin(limacon_driven_convexity)
    cosine = np.linspace(-1, 1, 401)
    assert min(derived([k], [m], [d.center_distance], [cosine])[0][0].min() for m in (m11, m12)) > 0


def test_derived_driven_convexity_matches_the_points():
    """Where the derived driven condition says concave, the driven points do turn both ways."""
    derived = numpy_twin(limacon_driven_convexity)
    cosine = np.linspace(-1, 1, 401)
    verdicts = []
    for k in (0.2, 0.4, 0.6):
        for m11 in (1.0, 1.5, 2.5, 3.0):
            m12 = denatured_partner(m11)
            d = design_pair(denatured_limacon(1.0, k, m11, m12), 1)
            convex = min(derived([k], [m], [d.center_distance], [cosine])[0][0].min() for m in (m11, m12)) > 0
            assert convex == _turns_one_way(d.points[1][:-1]), (k, m11)
            verdicts.append(convex)
    assert True in verdicts and False in verdicts


def test_kinematics_match_finite_differences_of_the_driven_angle():
    d = design_pair(limacon(40.0, 7.0, 2), 3, driver_speed=3.0)
    speed = np.gradient(d.phi2, d.phi1) * 3.0
    acceleration = np.gradient(speed, d.phi1) * 3.0
    inner = slice(5, -5)
    # central differences on a 720-step grid are accurate to O(h^2) ~ 1e-4 of the signal
    assert np.abs(speed - d.driven_speed)[inner].max() < 1e-4 * np.abs(d.driven_speed).max()
    assert np.abs(acceleration - d.driven_acceleration)[inner].max() < 1e-3 * np.abs(d.driven_acceleration).max()


def test_published_gear_of_the_onion_transplanter_paper():
    """Eq (19): m11 = 1.5 and 0.375 for the second half; Table 2: module 2, 55 teeth, center distance 110."""
    m12 = denatured_partner(1.5)
    assert m12 == pytest.approx(0.75)                    # eq (2): pi/1.5 + pi/m12 = 2 pi
    assert np.pi / 1.5 + np.pi / 0.375 == pytest.approx(10 * np.pi / 3)   # eq (19)'s value breaks eq (2)
    printed = denatured_limacon(53.0, 13.0, 1.5, 0.375)
    after, before = (printed.evaluate(np.array([2 * np.pi / 3 + side]))[0] for side in (1e-12, -1e-12))
    jump = after - before
    assert jump[0] == pytest.approx(13.0)                # r jumps from 40 to 53 mm at 120 deg
    d = design_pair(denatured_limacon(53.0, 13.0, 1.5, m12), 1)
    assert d.joints[0]["radius_jump"] == pytest.approx(0, abs=1e-9)
    assert d.joints[0]["slope_jump"] == pytest.approx(0, abs=1e-9)
    assert d.joints[0]["bend_jump"] == pytest.approx(13 * (0.75**2 - 1.5**2), rel=1e-6)   # curvature jumps
    assert d.center_distance == pytest.approx(109.0565, abs=1e-4)     # not 110
    assert d.perimeters[0] / (2 * np.pi) == pytest.approx(53.8935, abs=1e-4)   # teeth at module 2: not 55
    with pytest.raises(InfeasibleError, match="109.05648"):
        design_pair(denatured_limacon(53.0, 13.0, 1.5, m12), 1, center_distance=110.0)


def _circle_table(radius, samples=4001):
    angle = np.linspace(0, 2 * np.pi, samples)
    return pitch_table(radius * np.c_[np.cos(angle), np.sin(angle)], radius * angle,
                       np.c_[-np.sin(angle), np.cos(angle)])


def test_rack_envelope_on_a_circle_is_the_involute():
    table, alpha = _circle_table(30.0), np.radians(20)
    flank = _flank(table, 10.0, -1, alpha, 2.0, 400)
    tangent = np.gradient(flank, axis=0)
    normal = np.c_[tangent[:, 1], -tangent[:, 0]] / np.linalg.norm(tangent, axis=1)[:, None]
    # the profile normal of an involute is tangent to the base circle
    distance = np.abs(flank[:, 0] * normal[:, 1] - flank[:, 1] * normal[:, 0])
    assert np.abs(distance - 30.0 * np.cos(alpha))[2:-2].max() < 1e-4
    outline = rack_profile(table, 30, 2.0, alpha)
    radius, angle = np.hypot(*outline.T), np.unwrap(np.arctan2(outline[:, 1], outline[:, 0]))
    crossings = np.flatnonzero(np.diff(np.sign(radius - 30.0)))
    at_pitch = [angle[k] + (30 - radius[k]) / (radius[k + 1] - radius[k]) * (angle[k + 1] - angle[k])
                for k in crossings]
    assert np.abs(np.diff(at_pitch) * 30.0 - np.pi).max() < 2e-3     # tooth and space are p/2 = pi m / 2
    assert radius.min() == pytest.approx(27.5) and radius.max() == pytest.approx(32.0)


def _depth_inside(outline, points):
    """How far (mm) the deepest of ``points`` lies inside the polygon ``outline`` (0 when none is inside);
    exact, where matplotlib's contains_points with a radius reports points outside a polygon whose edges
    are shorter than that radius."""
    polygon = shapely.Polygon(outline)
    inside = shapely.contains_xy(polygon, points[:, 0], points[:, 1])
    return float(shapely.distance(polygon.exterior, shapely.points(points[inside])).max(initial=0.0))


def _scaled_pair(curve, teeth, module=2.0):
    return design_pair(curve.scaled(teeth * np.pi * module / design_pair(curve, 1).perimeters[0]), 1)


@functools.lru_cache(maxsize=1)
def _shaper_pair():
    """The shaper test pair, cut once for the tests that share it."""
    d = _scaled_pair(denatured_limacon(1.0, 0.45, 1.2, denatured_partner(1.2)), 52)
    return d, generate_teeth(d, 2.0, np.radians(20), "test", cutter="shaper", cutter_teeth=12)


@pytest.mark.parametrize("case", ["ellipse, rack", "concave denatured limacon, shaper"])
def test_teeth_mesh_without_interference(case):
    """Placed at many driver angles, neither gear enters the other by more than 0.02 mm, and they touch."""
    if case == "ellipse, rack":
        d = _scaled_pair(ellipse(1.0, 0.3), 30)
        teeth = generate_teeth(d, 2.0, np.radians(20), "test")
    else:
        # eq (9): 1 - (1.2^2 + 1) 0.45 < 0, concave; 52 teeth rather than the example's 60 (at 48 a module 2
        # would undercut the driven gear)
        d, teeth = _shaper_pair()
        assert (d.convexity[0] <= 0).any()      # the driver has a concave stretch
    assert teeth.self_intersections == (0, 0)
    driver, driven = teeth.outlines
    for k in range(0, len(d.phi1) - 1, 45):
        c1, s1 = np.cos(-d.phi1[k]), np.sin(-d.phi1[k])
        c2, s2 = np.cos(d.phi2[k]), np.sin(d.phi2[k])
        placed_driver = driver @ np.array([[c1, s1], [-s1, c1]])
        placed_driven = driven @ np.array([[c2, s2], [-s2, c2]]) + [d.center_distance, 0]
        pitch_point = [d.radius[0][k], 0]
        near_driver = placed_driver[np.linalg.norm(placed_driver - pitch_point, axis=1) < 10]
        near_driven = placed_driven[np.linalg.norm(placed_driven - pitch_point, axis=1) < 10]
        assert _depth_inside(placed_driven, near_driver) < 0.02
        assert _depth_inside(placed_driver, near_driven) < 0.02
        gap = cKDTree(placed_driven).query(near_driver)[0].min()
        assert gap < 0.05


def test_shaper_on_a_circle_cuts_the_involute():
    """A 40-tooth shaper on a circle leaves the involute of base radius R cos(alpha) on the flanks
    (compared with the exact rack envelope, to the 0.01 deg polar binning)."""
    table, alpha = _circle_table(30.0), np.radians(20)
    outline = shaper_profile(table, 2.0, alpha, 40)
    pitch = np.pi * 2.0
    exact = np.concatenate([_flank(table, k * pitch + side * pitch / 4 * -1, side, alpha, 2.0, 3000)
                            for k in range(30) for side in (1, -1)])
    radius = np.hypot(*outline.T)
    band = outline[(radius > 28.8) & (radius < 31.9)]
    gap = cKDTree(exact).query(band)[0]
    assert gap.max() < 0.005
    assert radius.min() == pytest.approx(27.5, abs=1e-9) and radius.max() == pytest.approx(32.0, abs=1e-9)


def test_shaper_pair_has_no_sampling_sliver():
    """On the shaper test pair the mesh check finds no overlap beyond 0.005 module: every arc bin
    of the mate holds the swept driver's exact lowest radius (a binned point cloud left one bin
    standing 0.028 mm into the driver near driver angle 4 deg). A driver cut without its teeth's
    sweep (the mate left as its bare blank) must fail the same check: the negative control."""
    d, teeth = _shaper_pair()
    driver, mate = teeth.outlines
    assert check_mesh(d, (driver, mate), 2.0).max_overlap_mm <= 0.005 * 2.0
    driven = driven_table(d)
    blank = driven.points + 2.0 * driven.normals
    assert check_mesh(d, (driver, blank), 2.0).max_overlap_mm > 0.005 * 2.0


def _straight_tipped_gear(radius, teeth, module):
    """A polygon gear: trapezoid teeth whose tip lands and roots are single straight edges."""
    pitch_angle = 2 * np.pi / teeth
    corners = []
    for k in range(teeth):
        middle = k * pitch_angle
        for offset, r in ((-0.30, radius - 1.25 * module), (-0.18, radius + module),
                          (0.18, radius + module), (0.30, radius - 1.25 * module)):
            corners.append(r * np.array([np.cos(middle + offset * pitch_angle), np.sin(middle + offset * pitch_angle)]))
    return np.array(corners)


def test_mate_of_a_straight_tipped_gear_is_cut_to_its_tip():
    """A straight tip land of length L sagging over the mate's pitch circle is a parabola in the mate's
    normal coordinates (sagitta about L^2 (1/R1 + 1/R2) / 8, 0.03 mm here). Cut by its chord
    ends alone, the mate kept that sliver in its roots and the placed polygons overlapped by it; with
    the edges split, no point of the driver's densified outline enters the cut mate by more than
    the overlap tolerance at any position."""
    module, radius = 2.0, 20.0
    d = _scaled_pair(ellipse(1.0, 0.0), 20, module)
    driver = _straight_tipped_gear(radius, 20, module)
    mate = mate_profile(d, driver, driven_table(d), module)
    dense = shapely.get_coordinates(shapely.segmentize(shapely.linearrings(driver), 0.01))
    depth = 0.0
    for phi1 in np.linspace(0, 2 * np.pi / 20, 9):
        phi2 = float(driven_angle(d, np.array([phi1]))[0])
        placed = rotate_about(rotate_about(dense, (0.0, 0.0), -phi1) - [d.center_distance, 0.0], (0.0, 0.0), -phi2)
        depth = max(depth, _depth_inside(mate, placed))
    assert depth < 0.005 * module
    assert check_mesh(d, (driver, mate), module).max_overlap_mm < 0.005 * module


def _resting_turn(design, outlines, module, phi1, steps=40):
    """Ground truth of the transmission error at driver angle phi1: the driven gear's turn from the design
    (rad, positive ahead) to where it just touches the driver on the driving flanks, by bisection on
    the overlap area of the two placed polygons near the pitch point."""
    a = design.center_distance
    phi2 = float(driven_angle(design, np.array([phi1]))[0])
    r1 = float(np.interp(np.mod(phi1, 2 * np.pi), design.phi1, design.radius[0]))
    driver = shapely.intersection(shapely.Polygon(rotate_about(outlines[0], (0.0, 0.0), -phi1)),
                                  shapely.Point(r1, 0.0).buffer(4 * module))
    driven = shapely.intersection(shapely.Polygon(rotate_about(outlines[1], (0.0, 0.0), phi2) + [a, 0.0]),
                                  shapely.Point(r1, 0.0).buffer(6 * module))
    touching = 1e-6 * module ** 2

    def overlaps(turn):
        placed = affinity.rotate(driven, turn, origin=(a, 0.0), use_radians=True)
        return shapely.intersection(driver, placed).area > touching

    # the nearest overlap-free turn to the design (it may overlap within tolerance), then towards the driver
    turns = np.arange(-40, 41) * 0.001 * module / (a - r1)
    free = min((turn for turn in turns if not overlaps(turn)), key=abs)
    blocked = -module / (a - r1)
    assert overlaps(blocked)
    for _ in range(steps):
        middle = (free + blocked) / 2
        free, blocked = (free, middle) if overlaps(middle) else (middle, blocked)
    return free


def test_shaper_pair_meshes_and_its_transmission_error_is_the_polygons():
    """The shaper test pair passes the mesh check, and where the check reports its largest transmission
    error (and at the two positions beside it) the placed polygons, the driven gear turned by bisection
    until it touches, agree with the check within a fifth of the tolerance. Before the envelope was
    taken along the pitch curve's normals, polar bins cut away the flanks of teeth leaning off the
    radius, and both the check and the polygons found 0.04 mm at driver angle 222.9 deg."""
    d, teeth = _shaper_pair()
    check = check_mesh(d, teeth.outlines, 2.0)
    assert check.passed, check.failures
    worst = int(np.argmax(np.abs(check.transmission_error * check.driven_pitch_radius)))
    for k in (worst - 1, worst, worst + 1):
        truth = _resting_turn(d, teeth.outlines, 2.0, check.driver_angle[k])
        gap = abs(truth - check.transmission_error[k]) * check.driven_pitch_radius[k]
        assert gap < 0.2 * ERROR_MODULES * 2.0


def test_shaper_too_large_for_the_concave_stretch():
    d = _scaled_pair(denatured_limacon(1.0, 0.45, 1.2, denatured_partner(1.2)), 60)
    with pytest.raises(InfeasibleError,
                       match=r"pair.shaper_teeth = 200: the cutter's pitch radius 200.000 mm does not fit"):
        generate_teeth(d, 2.0, np.radians(20), "test", cutter="shaper", cutter_teeth=200)


def test_undercut_and_concavity_are_refused_with_numbers():
    curve = ellipse(1.0, 0.5)
    d = design_pair(curve.scaled(12 * np.pi * 2.0 / design_pair(curve, 1).perimeters[0]), 1)   # 12 teeth of m = 2
    with pytest.raises(InfeasibleError, match=r"undercuts the driver: curvature radius .* below m / sin\^2"):
        generate_teeth(d, 2.0, np.radians(20), "test")


def test_undercut_advice_for_teeth_that_set_the_size_is_what_clears_it():
    """With pair.teeth setting the size, a smaller module shrinks the curve with it and never clears the undercut:
    the message's factor of teeth does. Its whole count just above clears the rack's criterion, just below not."""
    import math
    import re

    curve = ellipse(1.0, 0.5)

    def teeth_of(count):
        return design_pair(curve.scaled(count * np.pi * 2.0 / design_pair(curve, 1).perimeters[0]), 1)

    with pytest.raises(InfeasibleError,
                       match=r"where pair.teeth sets the size.*more teeth \(about ([\d.]+) times") as error:
        generate_teeth(teeth_of(12), 2.0, np.radians(20), "test")
    enough = math.ceil(12 * float(re.search(r"about ([\d.]+) times", str(error.value)).group(1)) - 1e-9)
    with pytest.raises(InfeasibleError, match="undercuts the driver"):
        generate_teeth(teeth_of(enough - 1), 2.0, np.radians(20), "test")
    try:
        generate_teeth(teeth_of(enough), 2.0, np.radians(20), "test")
    except InfeasibleError as refused:
        assert "undercut" not in str(refused)


def test_concave_pitch_curve_is_refused_for_the_rack():
    curve = denatured_limacon(1.0, 0.45, 1.2, denatured_partner(1.2))   # eq (9) < 0: concave driver
    d = design_pair(curve.scaled(40 * np.pi * 2.0 / design_pair(curve, 1).perimeters[0]), 1)
    with pytest.raises(InfeasibleError,
                       match="driver pitch curve is concave at phi1 = .* "
                             "rack cutter cannot generate it; set pair.cutter"):
        generate_teeth(d, 2.0, np.radians(20), "test")


def test_a_piece_narrower_than_a_panel_is_sampled_inside():
    """A denatured ellipse with m11 = 0.5001: its second piece spans pi / m12 = 0.07 deg and is concave inside; with
    one panel it was sampled at its two ends only, the rack's concavity check missed it and clipping a flank failed
    with an IndexError. Every piece now has PIECE_PANELS panels."""
    m11 = 0.5001
    curve = denatured_ellipse(40.0, 0.2, m11, denatured_partner(m11))
    d = design_pair(curve.scaled(40 * np.pi * 2.0 / design_pair(curve, 1).perimeters[0]), 1)
    inside = (d.phi1 > np.pi / m11) & (d.phi1 < 2 * np.pi)
    assert inside.sum() >= PIECE_PANELS - 1 and (d.convexity[0][inside] < 0).any()
    with pytest.raises(InfeasibleError, match="driver pitch curve is concave at phi1 = 359"):
        generate_teeth(d, 2.0, np.radians(20), "test")


def test_a_curve_too_sharp_for_the_quadrature_is_refused_as_such():
    """An order-12 ellipse with e = 0.99 (smallest radius 0.005 of the largest): the closing center distance found on
    the working quadrature does not close on the finer check; the message says so instead of naming a center
    distance the user never gave."""
    with pytest.raises(InfeasibleError, match=r"test: driver: the pitch curve varies too fast for the turn quadrature"):
        design_pair(ellipse(40.0, 0.99, 12), 12, source="test")


def _brute_force_crossings(outline):
    """Every pair of non-adjacent segments of the closed outline, each end strictly on both sides."""
    a, b = outline, np.roll(outline, -1, axis=0)
    i, j = np.triu_indices(len(a), 2)
    i, j = i[(j - i) < len(a) - 1], j[(j - i) < len(a) - 1]

    def side(p, q, r):
        return np.sign((q[:, 0] - p[:, 0]) * (r[:, 1] - p[:, 1]) - (q[:, 1] - p[:, 1]) * (r[:, 0] - p[:, 0]))

    return int(((side(a[i], b[i], a[j]) * side(a[i], b[i], b[j]) < 0)
                & (side(a[j], b[j], a[i]) * side(a[j], b[j], b[i]) < 0)).sum())


def test_self_intersection_count():
    from transplanter.gears.teeth import self_intersections
    t = np.linspace(0, 2 * np.pi, 2000, endpoint=False)
    outline = np.c_[np.cos(t), np.sin(t)] * (1 + 0.1 * np.cos(30 * t))[:, None]
    assert self_intersections(outline) == 0
    outline[[500, 501]] = outline[[501, 500]]          # two swapped vertices cross once
    assert self_intersections(outline) == 1


def test_self_intersections_of_constructed_outlines():
    """A figure-eight crosses once; a rack-cut gear outline is simple, and crosses itself once
    one flank is swung over its tooth's tip (counted as the brute force counts)."""
    from transplanter.gears.teeth import self_intersections
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False) + np.pi / 400      # no vertex at the crossing
    assert self_intersections(np.c_[np.sin(t), np.sin(t) * np.cos(t)]) == 1
    outline = rack_profile(_circle_table(20.0, 801), 20, 2.0, np.radians(20))
    assert self_intersections(outline) == 0 == _brute_force_crossings(outline)
    angle = np.arctan2(outline[:, 1], outline[:, 0])
    flank = np.flatnonzero((np.abs(angle - angle[0]) < 0.05) & (np.hypot(*outline.T) > 18.5))
    folded = outline.copy()
    c, s = np.cos(0.12), np.sin(0.12)
    folded[flank] = outline[flank] @ np.array([[c, s], [-s, c]])     # the flank swung over the tooth's tip
    assert self_intersections(folded) == _brute_force_crossings(folded) > 0


def test_self_intersections_match_brute_force_on_random_polylines(rng):
    from transplanter.gears.teeth import self_intersections
    counts = []
    for size in (3, 4, 5, 8, 20, 60, 200):
        for _ in range(5):
            outline = rng.normal(size=(size, 2))
            counts.append(self_intersections(outline))
            assert counts[-1] == _brute_force_crossings(outline)
    assert counts.count(0) > 5 and max(counts) > 1000


def test_analytic_ratio_is_corrected_to_close():
    """i12 = 1 + 0.35 cos(phi) + 0.1 sin(2 phi) does not close; with the constant factor k of Wang et al.
    2025, eq (12), the pair does, and its ratio is k times the formula at every sample."""
    from transplanter.gears.problem import parse_problem
    from transplanter.gears.synthesis import synthesize
    problem = parse_problem({"driver": {"family": "ratio", "expression": "1 + 0.35*cos(phi) + 0.1*sin(2*phi)",
                                             "correct": True}, "pair": {"center_distance": 80.0}})
    result = synthesize(problem)
    d = result.design
    formula = 1 + 0.35 * np.cos(d.phi1) + 0.1 * np.sin(2 * d.phi1)
    assert np.allclose(d.ratio, result.ratio_correction * formula, rtol=1e-12)
    assert result.ratio_correction != pytest.approx(1.0, abs=1e-3)
    assert abs(d.closure_error) < 1e-10 and d.center_distance == 80.0


@pytest.mark.parametrize("teeth", [8, 16, 60])
def test_pinion_cutter_flanks_are_involutes_of_its_base_circle(teeth):
    """Every edge of a flank between the base and tip circles has its normal tangent to the base circle, the teeth
    are as thick as the spaces on the pitch circle, and the outline is simple."""
    module, alpha = 2.0, np.radians(20)
    outline = shaper_cutter(module, alpha, teeth)
    radius, tip, lowest = shaper_cutter_radii(module, alpha, teeth)
    base = radius * np.cos(alpha)
    assert shapely.LinearRing(outline).is_simple
    edges = np.roll(outline, -1, axis=0) - outline
    middle = outline + edges / 2
    ends = np.hypot(*outline.T), np.hypot(*np.roll(outline, -1, axis=0).T)
    # edges that climb, above the base
    flank = (np.fmin(*ends) >= lowest - 1e-9) & (np.abs(ends[1] - ends[0]) > 1e-9)
    normal = np.c_[edges[:, 1], -edges[:, 0]] / np.hypot(*edges.T)[:, None]
    # distance from the centre to the normal through the edge's middle: the base radius, to second order in the edge
    reach_of_normal = np.abs(normal[flank, 0] * middle[flank, 1] - normal[flank, 1] * middle[flank, 0])
    assert flank.sum() >= 2 * teeth * 20 and np.abs(reach_of_normal - base).max() < 1e-3 * module
    pitch_circle = shapely.Point(0, 0).buffer(radius, quad_segs=4096).exterior
    crossings = shapely.get_coordinates(shapely.intersection(pitch_circle, shapely.LinearRing(outline)))
    angles = np.sort(np.mod(np.arctan2(crossings[:, 1], crossings[:, 0]), 2 * np.pi))
    widths = np.diff(np.r_[angles, angles[0] + 2 * np.pi])
    # on the pitch circle, to the sag of the flank's 40-point polyline (3e-4 mm at module 2)
    assert np.abs(widths - np.pi / teeth).max() * radius < 1e-3 * module

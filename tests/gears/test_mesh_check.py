"""The mesh check of a toothed pair: clean on rack-cut conjugate gears, and it catches a shifted tooth
and teeth cut on a pitch curve 0.05 mm off the designed one."""
import numpy as np
import pytest

from transplanter.gears.mesh_check import ERROR_MODULES, GAP_MODULES, OVERLAP_MODULES, check_mesh
from transplanter.gears.pair import design_pair
from transplanter.gears.pitch_curves import PitchCurve, ellipse
from transplanter.gears.rack_teeth import rack_profile
from transplanter.gears.teeth import driver_table, generate_teeth
from transplanter.geometry.poses import rotate_about

MODULE, ALPHA, TEETH = 2.0, np.radians(20), 30


@pytest.fixture(scope="module")
def pair():
    """An elliptical pair with 30 rack-cut teeth of module 2 on each gear."""
    curve = ellipse(1.0, 0.3)
    design = design_pair(curve.scaled(TEETH * np.pi * MODULE / design_pair(curve, 1).perimeters[0]), 1)
    return design, generate_teeth(design, MODULE, ALPHA, "test")


def test_rack_cut_pair_meshes_over_a_whole_turn(pair):
    design, teeth = pair
    check = check_mesh(design, teeth.outlines, MODULE)
    assert len(check.driver_angle) == 8 * TEETH
    assert check.passed, check.failures
    assert check.max_overlap_mm < OVERLAP_MODULES * MODULE
    assert check.max_contact_gap_mm < GAP_MODULES * MODULE          # touching at every position
    assert check.max_transmission_error_mm < ERROR_MODULES * MODULE
    assert np.all(check.play >= -1e-9)


def _shift_one_tooth(outline: np.ndarray, pitch_radius_of, fraction: float) -> np.ndarray:
    """The outline with one tooth (between the middles of its two neighbouring root gaps) turned about the
    centre by ``fraction`` of a pitch; the rest unchanged."""
    angle = np.arctan2(outline[:, 1], outline[:, 0])
    radius = np.hypot(*outline.T)
    root = radius < pitch_radius_of(angle) - 1.1 * MODULE            # root gaps are 1.25 modules deep
    starts = np.flatnonzero(root & ~np.roll(root, 1))
    ends = np.flatnonzero(root & ~np.roll(root, -1))
    following = ends[np.searchsorted(ends, starts) % len(ends)]
    middles = np.sort([(s + e) // 2 for s, e in zip(starts, following, strict=True)])
    first, second = middles[3], middles[4]
    shifted = outline.copy()
    turn = fraction * 2 * np.pi / TEETH
    c, s = np.cos(turn), np.sin(turn)
    piece = outline[first:second]
    shifted[first:second] = piece @ np.array([[c, s], [-s, c]])
    return shifted


@pytest.mark.parametrize("fraction", [0.02, -0.02])
def test_one_tooth_turned_by_a_fiftieth_of_a_pitch_is_caught(pair, fraction):
    """0.02 pitch is 0.126 mm of pitch arc at module 2: the driven gear's other teeth mesh, this one
    enters the driver (or leaves a gap, which the driving or coast flank shows as transmission error)."""
    design, teeth = pair
    driven = teeth.outlines[1]

    def pitch_radius(angle):
        phi2 = np.mod(np.pi - angle, 2 * np.pi)
        return np.interp(phi2, design.phi2, design.radius[1])

    check = check_mesh(design, (teeth.outlines[0], _shift_one_tooth(driven, pitch_radius, fraction)), MODULE)
    assert not check.passed
    assert check.max_overlap_mm > 5 * OVERLAP_MODULES * MODULE
    bad = check.clearance < -OVERLAP_MODULES * MODULE
    assert 0 < bad.sum() < 0.2 * len(bad)        # only while that tooth is in mesh


def test_teeth_cut_on_a_pitch_curve_off_by_005_mm_are_caught(pair):
    """The driver's teeth cut on its pitch curve plus a bump of 0.05 mm (a Gaussian 20 deg wide), meshed
    with the designed driven gear in the designed motion."""
    design, teeth = pair
    curve = design.driver
    centre, width, height = 2.0, np.radians(20), 0.05

    def bumped(phi):
        r, slope, bend = curve.evaluate(phi)
        u = (np.mod(phi - centre + np.pi, 2 * np.pi) - np.pi) / width
        g = height * np.exp(-u**2)
        return r + g, slope - 2 * u / width * g, bend + (4 * u**2 - 2) / width**2 * g

    perturbed = design_pair(PitchCurve("bumped", {}, 1, bumped, (), curve.breaks), 1)
    outline = rack_profile(driver_table(perturbed), TEETH, MODULE, ALPHA)
    check = check_mesh(design, (outline, teeth.outlines[1]), MODULE)
    assert not check.passed
    assert check.max_overlap_mm > 2 * OVERLAP_MODULES * MODULE or \
        check.max_transmission_error_mm > 2 * ERROR_MODULES * MODULE
    worst = check.driver_angle[np.argmin(check.clearance)]
    assert abs(np.mod(worst - centre + np.pi, 2 * np.pi) - np.pi) < 2 * width     # found where the bump is


@pytest.fixture(scope="module")
def circles():
    """Two 30-tooth circles of module 2 with rack-cut (involute) teeth: conjugate, no backlash."""
    circle = ellipse(1.0, 0.0)
    design = design_pair(circle.scaled(TEETH * np.pi * MODULE / design_pair(circle, 1).perimeters[0]), 1)
    return design, generate_teeth(design, MODULE, ALPHA, "test")


@pytest.mark.parametrize("turn_modules", [0.0, 0.015, -0.015])
def test_transmission_error_of_an_involute_pair_is_the_turn_given_to_the_driven_gear(circles, turn_modules):
    """The driven gear's outline turned ahead by a known angle must rest that far behind the design at
    every position (the definition of transmission error, positive ahead); untouched, it rests on the
    design. 0.015 module is three times the tolerance; agreement to a fifth of the tolerance."""
    design, teeth = circles
    radius = design.radius[1][0]
    turn = turn_modules * MODULE / radius
    driven = rotate_about(teeth.outlines[1], (0.0, 0.0), turn)
    check = check_mesh(design, (teeth.outlines[0], driven), MODULE)
    assert np.abs(check.transmission_error + turn).max() * radius < 0.2 * ERROR_MODULES * MODULE
    assert np.all(check.play >= -1e-9)
    assert check.passed == (turn_modules == 0.0)


def test_segment_grid_gives_every_points_nearest_segment_as_a_search_of_all_segments(pair, rng):
    """The grid's capped distance and nearest segment equal those of every segment searched (points spread about
    the tooth outline, so the cells list anything from none to dozens of segments; chunks of 500 points)."""
    from transplanter.gears.mesh_check import _SegmentGrid

    outline = pair[1].outlines[0]
    cap = 0.25 * MODULE
    grid = _SegmentGrid(outline, cap)
    points = outline[rng.integers(0, len(outline), 4000)] + rng.normal(0, 0.3 * MODULE, (4000, 2))
    distance, segment = grid.nearest(points, chunk=500)
    starts, steps = outline, np.roll(outline, -1, axis=0) - outline
    t = np.clip(np.einsum("psk,sk->ps", points[:, None] - starts, steps) / np.sum(steps ** 2, axis=1), 0, 1)
    every = np.linalg.norm(points[:, None] - starts - t[..., None] * steps, axis=2)
    least = every.min(axis=1)
    near = least < cap
    assert 0.2 < near.mean() < 0.95          # both kinds of points are there
    np.testing.assert_allclose(distance[near], least[near], rtol=0, atol=1e-12 * MODULE)
    assert np.all(distance[~near] == cap) and np.all(segment[~near] == -1)
    chosen = every[np.flatnonzero(near), segment[near]]          # the segment named is one of the nearest
    np.testing.assert_allclose(chosen, least[near], rtol=0, atol=1e-12 * MODULE)

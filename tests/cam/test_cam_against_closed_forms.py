"""Cams: the generated laws against their closed forms and finite differences, the pressure angle and
the curvature against closed forms derived here, cams built so their answer is known, design mode."""
import numpy as np
import pytest
import sympy as sp
from scipy.optimize import brentq
from shapely.geometry import LinearRing, Point

from transplanter import cam
from transplanter.cam.checks import acceleration_jumps, runs
from transplanter.cam.kinematics import evaluate, segment_motion
from transplanter.cam.problem import Segment
from transplanter.errors import ProblemError


def rise(angle, amount, law="harmonic", key="lift"):
    return {"kind": "rise", "angle_deg": angle, "law": law, key: amount}


def back(angle, amount, law="harmonic", key="lift"):
    return {"kind": "return", "angle_deg": angle, "law": law, key: amount}


def dwell(angle):
    return {"kind": "dwell", "angle_deg": angle}


def translating(base, roller, segments, offset=0.0, direction="counterclockwise", **extra):
    return cam.parse_problem({"cam": {"base_radius": base, "direction": direction}, **extra,
                              "follower": {"kind": "translating", "roller_radius": roller, "offset": offset},
                              "segments": segments})


def oscillating(base, roller, segments, pivot=(70.0, 0.0), arm=58.0, direction="counterclockwise", side="pulled"):
    return cam.parse_problem({"cam": {"base_radius": base, "direction": direction},
                              "follower": {"kind": "oscillating", "roller_radius": roller, "pivot": list(pivot),
                                           "arm_length": arm, "roller_side": side},
                              "segments": segments})


PROGRAM = [rise(110, 20.0), dwell(80), back(85, 20.0), dwell(85)]
SWING = [rise(110, 36.0, key="swing_deg"), dwell(80), back(85, 36.0, key="swing_deg"), dwell(85)]

# The laws' definitions as textbooks write them, y(tau) for a unit rise: an independent reference.
CLOSED_FORMS = {
    "harmonic": lambda t: (1 - np.cos(np.pi * t)) / 2,
    "cycloidal": lambda t: t - np.sin(2 * np.pi * t) / (2 * np.pi),
    "polynomial_345": lambda t: 10 * t**3 - 15 * t**4 + 6 * t**5,
}


@pytest.mark.parametrize("law", ["harmonic", "cycloidal", "polynomial_345", "modified_trapezoid"])
def test_law_derivatives_are_finite_differences_of_the_displacement(law):
    """v, a, j of each generated law are the central differences of s, v, a (away from the breaks of the
    modified trapezoid), and the law rises by its lift with zero velocity at both ends."""
    segment = Segment("rise", np.radians(80.0), law, 17.0)
    into = np.linspace(0.01, segment.angle - 0.01, 401)
    step = 1e-5
    here, ahead, behind = (segment_motion(segment, 3.0, into + d) for d in (0.0, step, -step))
    for order in range(3):
        difference = (ahead[order] - behind[order]) / (2 * step)
        scale = np.abs(here[order + 1]).max()
        assert np.abs(difference - here[order + 1]).max() < 1e-6 * scale, order
    ends = segment_motion(segment, 3.0, [0.0, segment.angle])
    assert ends[0] == pytest.approx([3.0, 20.0], abs=1e-12)
    assert np.abs(ends[1]).max() < 1e-12


@pytest.mark.parametrize("law", sorted(CLOSED_FORMS))
def test_law_is_its_closed_form(law):
    segment = Segment("return", np.radians(95.0), law, -12.0)
    into = np.linspace(0.0, segment.angle, 257)
    expected = 12.0 - 12.0 * CLOSED_FORMS[law](into / segment.angle)
    assert np.abs(segment_motion(segment, 12.0, into)[0] - expected).max() < 1e-12 * 12.0


def test_modified_trapezoid_peak_acceleration_and_continuity():
    """Acceleration continuous at the four breaks (1/8, 3/8, 5/8, 7/8) and zero at the ends; its peak is
    the textbook 4 pi / (2 + pi) = 4.8881 times lift / angle^2 (Norton's C_a), reached on the flat."""
    segment = Segment("rise", 1.0, "modified_trapezoid", 1.0)
    breaks = np.array([1, 3, 5, 7]) / 8
    left, right = segment_motion(segment, 0.0, breaks - 1e-12)[2], segment_motion(segment, 0.0, breaks + 1e-12)[2]
    assert np.abs(left - right).max() < 1e-9
    assert np.abs(segment_motion(segment, 0.0, [0.0, 1.0])[2]).max() < 1e-12
    peak = np.abs(segment_motion(segment, 0.0, np.linspace(0, 1, 4001))[2]).max()
    assert peak == pytest.approx(8 * np.pi / (2 + np.pi), rel=1e-12)


def _harmonic_pressure_closed_form():
    """Radial translating roller, harmonic rise h over beta from pitch radius r0: tan alpha = s'/(r0 + s) with
    s = h/2 (1 - cos x), s' = h pi/(2 beta) sin x, x = pi phi / beta. d/dx of tan alpha vanishes where
    cos x = h / (2 r0 + h); derived here with sympy, returned as a numpy function of (r0, h, beta)."""
    x, r0, h, beta = sp.symbols("x r0 h beta", positive=True)
    tan_alpha = (h * sp.pi / (2 * beta) * sp.sin(x)) / (r0 + h / 2 * (1 - sp.cos(x)))
    c = sp.Symbol("c")
    numerator = sp.expand(sp.numer(sp.together(sp.diff(tan_alpha, x))))
    (cosine,) = sp.solve(numerator.subs(sp.sin(x) ** 2, 1 - c**2).subs(sp.cos(x), c), c)
    assert sp.simplify(cosine - h / (2 * r0 + h)) == 0
    at_peak = sp.atan(tan_alpha.subs(x, sp.acos(cosine)))
    return (sp.lambdify((r0, h, beta), at_peak, "numpy"),
            sp.lambdify((r0, h, beta), beta * sp.acos(cosine) / sp.pi, "numpy"))


def test_pressure_angle_of_radial_harmonic_rise_is_its_closed_form():
    peak, where = _harmonic_pressure_closed_form()
    problem = translating(30.0, 10.0, [rise(60, 20.0), dwell(60), back(120, 20.0), dwell(120)])
    result = cam.synthesize(problem)
    assert result.checks.pressure["rise"].value == pytest.approx(peak(40.0, 20.0, np.radians(60)), rel=1e-10)
    assert result.checks.pressure["rise"].angle == pytest.approx(where(40.0, 20.0, np.radians(60)), rel=1e-6)
    assert result.checks.pressure["return"].value == pytest.approx(peak(40.0, 20.0, np.radians(120)), rel=1e-10)


def test_offset_follower_pressure_angle_is_the_classic_formula():
    """tan alpha = (s' - sigma e) / (sqrt(r0^2 - e^2) + s), both senses of rotation."""
    for direction, sigma in (("counterclockwise", 1), ("clockwise", -1)):
        g = evaluate(translating(30.0, 8.0, PROGRAM, offset=7.0, direction=direction), 30.0)
        s, v = g.motion[:2]
        expected = np.arctan2(v - sigma * 7.0, np.sqrt(38.0**2 - 7.0**2) + s)
        assert np.abs(g.pressure_angle - expected).max() < 1e-12


def test_smallest_pitch_radius_of_a_short_harmonic_rise_is_its_closed_form():
    """At the top of a harmonic rise the polar pitch curve r = r0 + s has r' = 0 and r'' = -h pi^2 / (2 beta^2),
    so its radius of curvature (r^2 + r'^2)^(3/2) / (r^2 + 2 r'^2 - r r'') is r^2 / (r - r''): here 24 mm,
    sharper than the base circle (40 mm), and the sharpest of the cam."""
    result = cam.synthesize(translating(30.0, 10.0, [rise(60, 20.0), dwell(60), back(120, 20.0), dwell(120)]))
    r, bend = 60.0, -20.0 * np.pi**2 / (2 * np.radians(60) ** 2)
    assert result.checks.min_pitch_radius.value == pytest.approx(r**2 / (r - bend), rel=1e-10)
    assert result.checks.min_pitch_radius.angle == pytest.approx(np.radians(60), abs=1e-6)
    assert result.checks.min_profile_radius.value == pytest.approx(r**2 / (r - bend) - 10.0, rel=1e-10)


def test_radial_pitch_curvature_is_the_polar_formula():
    g = evaluate(translating(25.0, 6.0, [rise(100, 15.0, "cycloidal"), dwell(50), back(130, 15.0, "polynomial_345"),
                                         dwell(80)]), 25.0)
    r, slope, bend = 31.0 + g.motion[0], g.motion[1], g.motion[2]
    polar = (r**2 + slope**2) ** 1.5 / (r**2 + 2 * slope**2 - r * bend)
    assert np.abs(g.curvature_radius - polar).max() < 1e-10 * polar.max()


def _periodic_difference(values, angle):
    step = angle[1] - angle[0]
    return (np.roll(values, -1, axis=0) - np.roll(values, 1, axis=0)) / (2 * step)


@pytest.mark.parametrize("make", [
    lambda: translating(28.0, 7.0, PROGRAM, offset=-6.0, direction="clockwise"),
    lambda: oscillating(30.0, 6.0, SWING),
    lambda: oscillating(30.0, 6.0, SWING, direction="clockwise", side="pushed"),
], ids=["offset translating", "oscillating pulled", "oscillating pushed clockwise"])
def test_pressure_angle_and_curvature_against_finite_differences(make):
    """From the sampled points alone: the pitch curve's normal (differences of its points, turned back to the
    ground) against the roller centre's direction of motion (differences of the centre) gives the pressure
    angle; the turning of the difference tangent gives the curvature radius. Compared away from segment ends."""
    problem = make()
    g = evaluate(problem, problem.base_radius, np.linspace(0, 2 * np.pi, 20000, endpoint=False))
    tangent = _periodic_difference(g.pitch, g.angle)
    second = (np.roll(g.pitch, -1, 0) - 2 * g.pitch + np.roll(g.pitch, 1, 0)) / (g.angle[1] - g.angle[0]) ** 2
    cross = tangent[:, 0] * second[:, 1] - tangent[:, 1] * second[:, 0]
    radius = -problem.direction * np.linalg.norm(tangent, axis=1) ** 3 / cross
    turn = problem.direction * g.angle
    c, s = np.cos(turn), np.sin(turn)
    ground = np.column_stack([c * tangent[:, 0] - s * tangent[:, 1], s * tangent[:, 0] + c * tangent[:, 1]])
    motion = _periodic_difference(g.center, g.angle)
    moving = np.linalg.norm(motion, axis=1) > 1e-6 * np.abs(g.center).max()
    unit = motion[moving] / np.linalg.norm(motion[moving], axis=1)[:, None]
    along = np.einsum("ij,ij->i", ground[moving], unit)
    across = np.abs(ground[moving, 0] * unit[:, 1] - ground[moving, 1] * unit[:, 0])
    away = np.ones(g.angle.size, bool)
    for start in np.cumsum([s.angle for s in problem.segments]):
        away &= np.abs((g.angle - start + np.pi) % (2 * np.pi) - np.pi) > 0.01
    measured = np.arctan2(np.abs(along), across)
    assert np.abs(measured - np.abs(g.pressure_angle[moving]))[away[moving]].max() < 1e-6
    curvature = 1 / g.curvature_radius          # compared as curvature: the radius is infinite at inflections
    assert np.abs(1 / radius - curvature)[away].max() < 1e-6 * np.abs(curvature).max()


@pytest.mark.parametrize("make", [lambda: translating(28.0, 7.0, PROGRAM, offset=4.0),
                                  lambda: oscillating(30.0, 6.0, SWING, direction="clockwise")])
def test_profile_is_the_roller_envelope(make):
    """Ground truth from the mechanism: the roller centre turned back with the cam stays on the follower's path
    (translating: x = offset; oscillating: at the arm length from the pivot, at the programmed swing), and the
    profile is at exactly the roller radius from every pitch point, and nowhere nearer (shapely distances)."""
    problem = make()
    result = cam.synthesize(problem)
    g = result.geometry
    turn = problem.direction * g.angle
    c, s = np.cos(turn), np.sin(turn)
    ground = np.column_stack([c * g.pitch[:, 0] - s * g.pitch[:, 1], s * g.pitch[:, 0] + c * g.pitch[:, 1]])
    follower = problem.follower
    if follower.kind == "translating":
        assert np.abs(ground[:, 0] - follower.offset).max() < 1e-12 * 40
        assert np.abs(ground[:, 1] - ground[0, 1] - g.motion[0]).max() < 1e-12 * 40
    else:
        arm = ground - follower.pivot
        assert np.abs(np.linalg.norm(arm, axis=1) - follower.arm_length).max() < 1e-12 * 100
        swing = np.unwrap(np.arctan2(arm[:, 1], arm[:, 0]))
        assert np.abs(np.abs(swing - swing[0]) - g.motion[0]).max() < 1e-12
    ring = LinearRing(g.profile)
    distance = np.array([ring.distance(Point(p)) for p in g.pitch[::10]])
    assert np.abs(distance - follower.roller_radius).max() < 1e-6 * follower.roller_radius
    assert not result.checks.undercut and not result.checks.interference


def test_concave_profile_radius_is_pitch_radius_plus_roller():
    """On concave stretches the profile's radius, from differences of its own points, is |rho_pitch| + R_r: the
    reason a roller always fits the concave stretches of an offset profile (docs/cam.md)."""
    problem = translating(20.0, 9.0, [rise(70, 30.0, "cycloidal"), dwell(60), back(70, 30.0, "cycloidal"), dwell(160)])
    g = evaluate(problem, 20.0, np.linspace(0, 2 * np.pi, 20000, endpoint=False))
    step = g.angle[1] - g.angle[0]
    tangent = _periodic_difference(g.profile, g.angle)
    second = (np.roll(g.profile, -1, 0) - 2 * g.profile + np.roll(g.profile, 1, 0)) / step**2
    radius = -np.linalg.norm(tangent, axis=1) ** 3 / (tangent[:, 0] * second[:, 1] - tangent[:, 1] * second[:, 0])
    concave = g.curvature_radius < 0
    assert concave.sum() > 100
    curvature = 1 / g.profile_curvature_radius[concave]
    assert np.abs(1 / radius[concave] - curvature).max() < 1e-6 * np.abs(curvature).max()
    assert (np.abs(g.profile_curvature_radius[concave]) > 9.0).all()


def test_undercut_appears_exactly_when_the_roller_outgrows_the_sharpest_pitch_radius():
    """Harmonic rise of 20 mm over 40 deg from pitch radius r0 = 40: the sharpest pitch radius is
    r^2 / (r - r'') at the top (closed form above), 13.714 mm. Keeping r0 at 40, a roller 0.1 mm smaller passes
    and one 0.1 mm larger undercuts there, and its swallowtail makes the roller cut into the profile."""
    program = [rise(40, 20.0), dwell(80), back(120, 20.0), dwell(120)]
    sharpest = 60.0**2 / (60.0 + 20.0 * np.pi**2 / (2 * np.radians(40) ** 2))
    limits = {"limits": {"pressure_angle_deg": 80.0}}
    fits = cam.synthesize(translating(40.0 - (sharpest - 0.1), sharpest - 0.1, program, **limits))
    assert fits.passed and fits.checks.min_pitch_radius.value == pytest.approx(sharpest, rel=1e-10)
    cuts = cam.synthesize(translating(40.0 - (sharpest + 0.1), sharpest + 0.1, program, **limits))
    assert not cuts.passed
    (stretch,) = cuts.checks.undercut
    assert stretch.start <= np.radians(40) <= stretch.end + 2 * np.pi / 3600
    assert stretch.worst == pytest.approx(sharpest, rel=1e-4)
    assert cuts.checks.interference and "undercut" in cuts.failures[0]


def test_acceleration_jumps_of_harmonic_motion_between_dwells():
    """A harmonic rise between dwells starts and stops with acceleration +-h pi^2 / (2 beta^2): two jumps of that
    size; a harmonic rise straight into a harmonic return of the same angle meets with equal acceleration (no
    jump); cycloidal, 3-4-5 and modified trapezoid between dwells have none."""
    problem = translating(30.0, 6.0, [rise(90, 20.0), dwell(90), back(90, 20.0, "cycloidal"), dwell(90)])
    size = 20.0 * np.pi**2 / (2 * (np.pi / 2) ** 2)
    jumps = acceleration_jumps(problem)
    assert [(round(np.degrees(j.angle)), j.before, j.after) for j in jumps] == [(90, 0, 1), (0, 3, 0)]
    assert [j.size for j in jumps] == pytest.approx([size, size], rel=1e-12)
    assert not acceleration_jumps(translating(30.0, 6.0, [rise(180, 20.0), back(180, 20.0)]))
    for law in ("cycloidal", "polynomial_345", "modified_trapezoid"):
        assert not acceleration_jumps(translating(30.0, 6.0, [rise(90, 20.0, law), dwell(90), back(90, 20.0, law),
                                                              dwell(90)]))


def test_design_mode_finds_the_closed_form_base_circle():
    """A radial translating follower with harmonic rise and return: the pressure angle peaks on the shorter
    segment, and the closed form above set equal to the limit gives r0; design mode returns r0 - R_r, and its
    cam meets the limit at that size and not 0.1 % below it (an independent evaluation of both)."""
    peak, _ = _harmonic_pressure_closed_form()
    limit = np.radians(30.0)
    r0 = brentq(lambda r: peak(r, 25.0, np.radians(100)) - limit, 10.0, 500.0)
    problem = cam.parse_problem({"cam": {"samples": 1440}, "design": {"max_base_radius": 300.0},
                                 "follower": {"kind": "translating", "roller_radius": 5.0},
                                 "segments": [rise(100, 25.0), dwell(60), back(140, 25.0), dwell(60)]})
    result = cam.synthesize(problem)
    assert result.designed and result.passed
    assert result.base_radius == pytest.approx(r0 - 5.0, rel=1e-6)
    smaller = cam.synthesize(cam.parse_problem({**_as_analysis(problem), "cam": {"base_radius": 0.999 * (r0 - 5.0)}}))
    assert not smaller.passed and "pressure angle on rise" in smaller.failures[0]


def _as_analysis(problem):
    return {"follower": {"kind": "translating", "roller_radius": problem.follower.roller_radius},
            "segments": [rise(100, 25.0), dwell(60), back(140, 25.0), dwell(60)]}


def test_runs_wrap_through_zero():
    mask = np.array([True, True, False, False, True, False, True])
    assert [r.tolist() for r in runs(mask)] == [[4], [6, 0, 1]]
    assert [r.tolist() for r in runs(np.ones(3, bool))] == [[0, 1, 2]]


def test_flat_faced_profile_radius_is_base_plus_s_plus_s2():
    """The envelope of the face lines, derived in derivations/cam.py, has the curvature radius R_b + s + s''
    (the support function's h + h'') and the contact sits s' along the face, in either sense of rotation."""
    from derivations.cam import flat_faced_profile

    theta, base, s, v, a = sp.symbols("theta b s v a", real=True)
    for sense in (1, -1):
        _, radius, contact = flat_faced_profile(theta, sp.Integer(sense), base, s, v, a)
        assert sp.simplify(radius - (base + s + a)) == 0
        assert sp.simplify(contact - sense * v) == 0


def _flat(base, segments, direction="counterclockwise", design=None):
    data = {"cam": {"direction": direction, **({} if design else {"base_radius": base})},
            "follower": {"kind": "flat_faced"}, "segments": segments}
    if design:
        data["design"] = {"max_base_radius": design}
    return cam.parse_problem(data)


def test_flat_faced_cam_touches_every_face_position_and_crosses_none():
    """Ground truth: turned back with the cam, the profile point of each angle lies on that angle's face line
    y = R_b + s, and no profile point rises above any face line (the face is the envelope's tangent)."""
    problem = _flat(40.0, PROGRAM, direction="clockwise")
    result = cam.synthesize(problem)
    g = result.geometry
    turn = problem.direction * g.angle
    c, s = np.cos(turn), np.sin(turn)
    ground_y = s * g.profile[:, 0] + c * g.profile[:, 1]
    assert np.abs(ground_y - (40.0 + g.motion[0])).max() < 1e-12 * 60
    heights = s[::20, None] * g.profile[None, :, 0] + c[::20, None] * g.profile[None, :, 1]
    assert (heights <= (40.0 + g.motion[0][::20, None]) * (1 + 1e-12)).all()
    assert result.passed and result.checks.pressure["rise"].value == 0.0
    offsets = result.to_json()["follower"]["face_offset_range_mm"]
    assert offsets == pytest.approx([-g.motion[1].max(), -g.motion[1].min()], rel=1e-12)    # clockwise: -s'


def test_flat_faced_design_finds_the_closed_form_base_circle():
    """Harmonic rise of 20 mm over 40 deg: R_b + s + s'' is least at the top of the rise, R_b + 20 - 20 pi^2 / (2
    beta^2); the face can follow only where it is positive, so the smallest base circle is 20 pi^2 / (2 beta^2) - 20
    = 182.52 mm. Design mode finds it; 1 % smaller fails on a stretch around the top of the rise."""
    program = [rise(40, 20.0), dwell(80), back(120, 20.0), dwell(120)]
    expected = 20.0 * np.pi**2 / (2 * np.radians(40) ** 2) - 20.0
    result = cam.synthesize(_flat(None, program, design=400.0))
    assert result.base_radius == pytest.approx(expected, rel=1e-6)
    smaller = cam.synthesize(_flat(0.99 * expected, program))
    (stretch,) = smaller.checks.undercut
    assert stretch.start <= np.radians(40) <= stretch.end + 2 * np.pi / 3600
    assert not smaller.passed and "flat face cannot follow" in smaller.failures[0]


def test_profile_radius_limit_moves_the_flat_faced_design_by_itself():
    """R_b + s + s'' grows one for one with R_b, so asking the profile for a 3 mm radius moves the smallest base
    circle up by exactly 3 mm (here 182.52 + 3); analysed 0.1 mm below, the cam fails on that limit."""
    program = [rise(40, 20.0), dwell(80), back(120, 20.0), dwell(120)]
    expected = 20.0 * np.pi**2 / (2 * np.radians(40) ** 2) - 20.0 + 3.0
    data = {"cam": {}, "follower": {"kind": "flat_faced"}, "segments": program,
            "limits": {"profile_radius_mm": 3.0}, "design": {"max_base_radius": 400.0}}
    result = cam.synthesize(cam.parse_problem(data))
    assert result.base_radius == pytest.approx(expected, rel=1e-6)
    assert result.checks.min_profile_radius.value == pytest.approx(3.0, rel=1e-5)
    analysis = {key: value for key, value in data.items() if key != "design"} | {"cam": {"base_radius": expected - 0.1}}
    below = cam.synthesize(cam.parse_problem(analysis))
    assert not below.passed and "limits.profile_radius_mm = 3" in below.failures[0]


def test_swing_bound_is_where_the_roller_reaches_its_farthest_point():
    """The largest swing an oscillating follower may ask is 180 deg less the rest angle at the pivot (cosine rule):
    just below it the roller centre comes within 1e-3 mm of pivot distance + arm and the rise's pressure angle
    nears 90 deg; at it the problem is refused, naming the bound."""
    reach, arm, pitch = 70.0, 58.0, 36.0
    bound = 180.0 - np.degrees(np.arccos((reach**2 + arm**2 - pitch**2) / (2 * reach * arm)))

    def program(swing):
        return [rise(110, swing, key="swing_deg"), dwell(80), back(85, swing, key="swing_deg"), dwell(85)]

    result = cam.synthesize(oscillating(30.0, 6.0, program(0.999 * bound)))
    assert np.max(np.hypot(*result.geometry.center.T)) == pytest.approx(reach + arm, abs=1e-3)
    assert np.degrees(result.checks.pressure["rise"].value) > 89.9
    with pytest.raises(ProblemError, match=f"less than {bound:.6g} deg"):
        oscillating(30.0, 6.0, program(bound))

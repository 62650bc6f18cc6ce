"""The onion transplanter of the onion-transplanter paper, the derived model: gear pair, kinematics, trajectory
measures."""
import dataclasses
from itertools import pairwise

import numpy as np
import pytest
import sympy as sp
from scipy.integrate import quad
from scipy.optimize import brentq

from derivations import parallelogram as derivation
from transplanter.gears.pair import design_pair
from transplanter.gears.pitch_curves import denatured_limacon
from transplanter.parallelogram.kinematics import closing_center_distance, mechanisms
from transplanter.parallelogram.problem import Conventions, parse_problem
from transplanter.parallelogram.trajectory import measure

PUBLISHED = dict(m11=1.5, b=13.0, l=53.0, l1=82.0, l2=254.0, l5=61.0, l6=119.0, alpha_deg=6.0)


def _problem(**changes):
    design = {**PUBLISHED, **changes.pop("design", {})}
    return parse_problem({"design": design, **changes})


def test_antiderivative_of_the_rolling_law():
    """dF/du = r1 / (a - r1) for r1 = l + b cos u (the closed form behind phi2), at seeded points."""
    u, a, base, b = sp.symbols("u a l b", real=True)
    residual = derivation.driven_antiderivative_residual(u, a, base, b)
    rng = np.random.default_rng(1)
    for _ in range(6):
        point = {u: rng.uniform(0, np.pi), base: rng.uniform(30, 60), b: rng.uniform(1, 20)}
        point[a] = point[base] + point[b] + rng.uniform(5, 60)
        assert abs(float(residual.subs(point))) < 1e-12


@pytest.mark.parametrize("m12,center", [(None, None), (0.375, 110.0), (0.75, 110.0)])
def test_driven_angle_against_quadrature_of_the_gear_library_curve(m12, center):
    """phi2(phi1) in closed form equals int r1/(a - r1) of the gear library's pitch curve (scipy quad)."""
    problem = _problem()
    mech = mechanisms(problem, m12=m12, center_distance=center)
    curve = denatured_limacon(53.0, 13.0, 1.5, float(mech.m12[0]))
    a = float(mech.center_distance[0])
    phi = np.array([0.3, 1.9, 2 * np.pi / 3, 2.5, 4.0, 2 * np.pi])
    def radius(x):
        return float(curve.evaluate(np.array([x]))[0][0])

    for x, value in zip(phi, mech.driven_angle(np.broadcast_to(phi, (1, phi.size)))[0], strict=True):
        pieces = [0.0, min(x, 2 * np.pi / 3), x]
        expected = sum(quad(lambda s: radius(s) / (a - radius(s)), p, q, epsabs=1e-13)[0]
                       for p, q in pairwise(pieces) if q > p)
        assert value == pytest.approx(expected, rel=1e-10, abs=1e-12)


def test_closing_center_distance_is_the_gear_library_closure():
    """The closed form (gear library's limacon closure at order ratio 1) closes the denatured pair,
    whatever m11: the gear library's numerical closure agrees and phi2(2 pi) = 2 pi."""
    for m11 in (0.8, 1.5, 2.5):
        numeric = design_pair(denatured_limacon(53.0, 13.0, m11, 1 / (2 - 1 / m11)), 1).center_distance
        assert closing_center_distance(np.array([53.0]), np.array([13.0]))[0] == pytest.approx(numeric, rel=1e-12)
        mech = mechanisms(_problem(design={"m11": m11}))
        assert mech.driven_turn[0] == pytest.approx(2 * np.pi, rel=1e-12)


def _uniform_crank(ratio_center, forward, l1=80.0, speed=2 * np.pi, sense="counterclockwise"):
    """b = 0: a circular pair r1 = l, phi2 = phi1 l / (a - l) exactly; alpha 0 from +x at phi1 = 0."""
    return _problem(design={"b": 1e-300, "l": 50.0, "l1": l1, "alpha_deg": 0.0},
                    machine={"forward_speed_mm_s": forward, "forward": "-x",
                             "driver_speed_rpm": speed * 60 / (2 * np.pi), "crank_pivot_mm": [7.0, -3.0]},
                    conventions={"crank_sense": sense, "alpha_reference_deg": 0.0, "alpha_instant": "driver_zero"})


@pytest.mark.parametrize("sense", ["counterclockwise", "clockwise"])
def test_kinematics_of_a_constructed_motion(sense):
    """Circular gears at a = 3 l turn the crank at half the driver's speed: A and E on a circle of radius l1
    about O2, E offset by (l2 + l5, -l6), the machine's travel added; velocity and acceleration in closed form."""
    problem = _uniform_crank(None, 250.0, sense=sense)
    mech = mechanisms(problem, center_distance=150.0)
    s = 1.0 if sense == "counterclockwise" else -1.0
    phi = np.array([[0.0, 1.0, 2.5, 4.0, 6.0, 9.5]])
    t = phi / problem.driver_speed
    omega = s * problem.driver_speed / 2
    theta = s * phi / 2
    pin, tip, velocity, acceleration = mech.state(phi)
    pivot = np.array([150.0 + 7.0, -3.0])
    expected_pin = pivot[:, None] + 80.0 * np.array([np.cos(theta[0]), np.sin(theta[0])])
    assert np.allclose(pin[:, 0], expected_pin, rtol=0, atol=1e-11 * 80)
    expected_tip = pin[:, 0] + np.array([[254.0 + 61.0], [-119.0]]) + np.array([-250.0 * t[0], 0 * t[0]])
    assert np.allclose(tip[:, 0], expected_tip, rtol=0, atol=1e-10 * 80)
    expected_velocity = np.array([-80 * omega * np.sin(theta[0]) - 250.0, 80 * omega * np.cos(theta[0])])
    assert np.allclose(velocity[:, 0], expected_velocity, rtol=0, atol=1e-10 * 80 * abs(omega))
    expected_acceleration = -80 * omega**2 * np.array([np.cos(theta[0]), np.sin(theta[0])])
    assert np.allclose(acceleration[:, 0], expected_acceleration, rtol=0, atol=1e-10 * 80 * omega**2)


def test_velocity_and_acceleration_are_the_derivatives_of_the_positions():
    """Exact velocity and acceleration of E against central differences in time (published design,
    away from the joint at 120 deg, where the acceleration jumps)."""
    mech = mechanisms(_problem())
    phi = np.array([0.4, 1.3, 3.0, 4.4, 5.9, 7.1])
    h = 1e-4
    dt = h / mech.driver_speed
    def tip(x):
        return mech.state(x[None, :])[1][:, 0]

    velocity = mech.state(phi[None, :])[2][:, 0]
    acceleration = mech.state(phi[None, :])[3][:, 0]
    differences = (tip(phi + h) - tip(phi - h)) / (2 * dt)
    second = (tip(phi + h) - 2 * tip(phi) + tip(phi - h)) / dt**2
    assert np.abs(velocity - differences).max() <= 1e-6 * np.abs(velocity).max()
    assert np.abs(acceleration - second).max() <= 1e-4 * np.abs(acceleration).max()


def test_vertical_range_is_twice_the_crank_for_any_design(rng):
    """Y = 2 l1 whenever the crank turns fully (closed pairs, random designs and phases)."""
    count = 40
    variables = {"m11": rng.uniform(0.8, 2.5, count), "b": rng.uniform(2, 20, count), "l": rng.uniform(40, 70, count),
                 "l1": rng.uniform(30, 120, count), "alpha": rng.uniform(-np.pi, np.pi, count)}
    problem = _problem()
    m = measure(mechanisms(problem, variables), problem.depth_window, 512)
    assert np.allclose(m.vertical_range, 2 * variables["l1"], rtol=1e-12, atol=0)


@pytest.mark.parametrize("speed_ratio", [1.0, 0.8, 1.15])
def test_depth_and_release_speed_of_a_trochoid(speed_ratio):
    """A uniform crank of radius R and speed w with the machine at v gives a trochoid whose lowest point
    moves at R w - v; near it X - X_E = R sin s - (v/w) s and Y - Y_E = R (1 - cos s) (s the crank's
    turn past the bottom), so the depth is R (1 - cos s*) at the s* where |X - X_E| = w_H, solved here
    with brentq on that formula."""
    radius, w = 80.0, 2 * np.pi
    v = speed_ratio * radius * w
    problem = _uniform_crank(None, v, l1=radius, speed=w)
    mech = mechanisms(problem, center_distance=100.0)   # a = 2 l: phi2 = phi1
    m = measure(mech, problem.depth_window, 1024)
    assert m.vx_release[0] == pytest.approx(radius * w - v, abs=1e-9 * radius * w)
    window = problem.depth_window
    def gap(s):
        return abs(radius * np.sin(s) - v / w * s) - window

    ends = [brentq(gap, side * 1e-9, side * np.pi) for side in (-1, 1)]
    expected = max(radius * (1 - np.cos(s)) for s in ends)
    assert m.depth[0] == pytest.approx(expected, rel=1e-9)
    assert m.spacing[0] == pytest.approx(v * 2 * np.pi / w, rel=1e-12)


def test_translation_only_parameters_have_zero_derivatives():
    """l2, l5, l6 and the crank pivot enter E as a constant offset: the derived velocity and acceleration
    do not depend on them (symbolic Jacobian zero), and neither do the measures (numeric)."""
    phi1, omega, v, phase, sense = sp.symbols("phi1 omega v phase sense", real=True)
    gear = sp.symbols("a l b m11 m12", positive=True)
    links = sp.symbols("l1 l2 l5 l6", positive=True)
    pivot = sp.symbols("x0 y0", real=True)
    jacobian = derivation.translation_parameter_derivatives(phi1, gear, pivot, links, phase, sense, omega, v)
    assert jacobian.is_zero_matrix
    problem = _problem()
    base = measure(mechanisms(problem), problem.depth_window, 2048)
    moved = measure(mechanisms(dataclasses.replace(problem, crank_pivot=np.array([40.0, -25.0])),
                               {"l2": 300.0, "l5": 10.0, "l6": 230.0}), problem.depth_window, 2048)
    for name in ("depth", "vx_release", "vertical_range", "spacing", "planting_time"):
        assert getattr(moved, name) == pytest.approx(getattr(base, name), rel=1e-9, abs=1e-9)


def test_driven_angle_sees_only_the_shape_of_the_pair():
    """phi2 is homogeneous of degree 0 in (a, l, b) (Euler's identity, at seeded points): scaling the gear
    pair, e.g. to whole teeth, leaves the trajectory as it was."""
    phi1 = sp.Symbol("phi1", real=True)
    gear = sp.symbols("a l b m11 m12", positive=True)
    euler = derivation.driven_angle_scale_derivative(phi1, gear)
    rng = np.random.default_rng(3)
    for x in (0.7, 3.5):
        point = {phi1: x, gear[1]: rng.uniform(40, 60), gear[2]: rng.uniform(5, 15),
                 gear[3]: 1.4, gear[4]: 1 / (2 - 1 / 1.4)}
        point[gear[0]] = point[gear[1]] + point[gear[2]] + 40
        assert abs(float(euler.subs(point))) < 1e-12
    problem = _problem()
    base = measure(mechanisms(problem), problem.depth_window, 2048)
    scaled = measure(mechanisms(problem, {"b": 13.0 * 1.7, "l": 53.0 * 1.7}), problem.depth_window, 2048)
    assert scaled.depth == pytest.approx(base.depth, rel=1e-9)
    assert scaled.vx_release == pytest.approx(base.vx_release, rel=1e-9, abs=1e-9)


def test_conventions_mirror():
    """Reversing the crank and the travel together, with the reference mirrored, mirrors the path:
    same depth, opposite Vx."""
    problem = _problem()
    c = problem.conventions
    mirrored = dataclasses.replace(problem, conventions=Conventions(-c.crank_sense, np.pi - c.alpha_reference,
                                                                     c.alpha_instant, -c.forward))
    a, b = (measure(mechanisms(p), p.depth_window, 2048) for p in (problem, mirrored))
    assert b.depth == pytest.approx(a.depth, rel=1e-9)
    assert b.vx_release == pytest.approx(-a.vx_release, rel=1e-9)


def test_position_grid_function_is_the_tip_without_the_travel():
    """``parallelogram_position`` (dense grids) equals ``parallelogram_tip`` less the machine's travel."""
    mech = mechanisms(_problem())
    phi = np.array([[0.2, 2.0, 2.2, 5.0, 8.0]])
    travel = np.array([[mech.forward_velocity], [0.0]]) * phi / mech.driver_speed
    assert np.allclose(mech.position(phi)[:, 0], mech.state(phi)[1][:, 0] - travel, rtol=0, atol=1e-12 * 500)

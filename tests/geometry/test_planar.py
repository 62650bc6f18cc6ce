"""The plane-vector helpers: known values, broadcasting, and the CasADi twins against numpy."""
import casadi as ca
import numpy as np
import pytest

from transplanter.geometry.planar import (
    TWO_PI,
    casadi_cross,
    casadi_rotate,
    casadi_unit,
    cross,
    modulo,
    rotate,
    unit,
)


def test_rotate_turns_counterclockwise_by_a_known_angle():
    assert rotate(np.pi / 2, [1.0, 0.0]) == pytest.approx([0.0, 1.0], abs=1e-15)
    assert rotate(np.pi / 6, [2.0, 0.0]) == pytest.approx([np.sqrt(3.0), 1.0], abs=1e-15)
    assert rotate(-np.pi / 2, [0.0, 3.0]) == pytest.approx([3.0, 0.0], abs=1e-15)
    assert rotate(TWO_PI, [0.3, -0.7]) == pytest.approx([0.3, -0.7], abs=1e-15)


def test_modulo_gives_numpys_remainder(rng):
    """From -period to 2 period, np.mod's remainder exactly (the multiples of the period included); a few periods
    out, to rounding; next to a multiple, 0 or period to rounding."""
    period = 377.123
    values = np.r_[rng.uniform(-period, 2 * period, 100000), np.arange(-1, 2) * period]
    assert np.array_equal(modulo(values, period), np.mod(values, period))
    values = rng.uniform(-5 * period, 5 * period, 100000)
    assert np.abs(modulo(values, period) - np.mod(values, period)).max() < 1e-14 * 5 * period
    multiples = np.arange(-5, 6) * period
    near = modulo(np.r_[np.nextafter(multiples, np.inf), np.nextafter(multiples, -np.inf)], period)
    assert (np.minimum(np.abs(near), np.abs(near - period)) < 1e-14 * 5 * period).all()


def test_cross_is_positive_when_the_second_vector_points_counterclockwise_of_the_first():
    assert cross(np.array([1.0, 0.0]), np.array([0.0, 2.0])) == 2.0
    assert cross(np.array([0.0, 2.0]), np.array([1.0, 0.0])) == -2.0
    assert cross(np.array([1.0, 1.0]), np.array([-3.0, -3.0])) == 0.0


def test_numpy_helpers_broadcast_over_leading_axes(rng):
    angles = rng.uniform(-np.pi, np.pi, (4, 3))
    vectors = rng.normal(size=(3, 2))
    assert unit(angles).shape == (4, 3, 2)
    turned = rotate(angles, vectors)
    assert turned.shape == (4, 3, 2)
    assert turned[2, 1] == pytest.approx(rotate(angles[2, 1], vectors[1]), abs=1e-15)
    assert cross(unit(angles), vectors).shape == (4, 3)
    # turning the unit vector at b by a gives the unit vector at a + b; a turn keeps lengths and cross products
    others = rng.uniform(-np.pi, np.pi, (4, 3))
    assert rotate(angles, unit(others)) == pytest.approx(unit(angles + others), abs=1e-14)
    assert np.linalg.norm(turned, axis=-1) == pytest.approx(np.broadcast_to(np.linalg.norm(vectors, axis=-1), (4, 3)))
    assert cross(turned, rotate(angles, vectors[::-1])) == pytest.approx(
        np.broadcast_to(cross(vectors, vectors[::-1]), (4, 3)), abs=1e-12)


@pytest.mark.parametrize("symbol", [ca.SX, ca.MX])
def test_casadi_twins_agree_with_numpy_at_seeded_points(symbol, rng):
    angle, u, v = symbol.sym("angle"), symbol.sym("u", 2), symbol.sym("v", 2)
    twins = ca.Function("twins", [angle, u, v], [casadi_unit(angle), casadi_rotate(angle, u), casadi_cross(u, v)])
    for _ in range(20):
        a, p, q = rng.uniform(-10, 10), rng.normal(size=2) * 100, rng.normal(size=2) * 100
        unit_value, rotated, crossed = (np.asarray(value).ravel() for value in twins(a, p, q))
        assert unit_value == pytest.approx(unit(a), rel=1e-15, abs=1e-15)
        assert rotated == pytest.approx(rotate(a, p), rel=1e-14, abs=1e-12)
        assert crossed == pytest.approx([cross(p, q)], rel=1e-14, abs=1e-10)

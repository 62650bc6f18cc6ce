"""The foot of a point's normal on a pitch table, converged, against bisection on the normal condition; the swept
tooth outlines built on it against the same outlines built on bisection."""
import dataclasses
from pathlib import Path

import numpy as np
import pytest
from scipy.spatial import cKDTree

from transplanter.gears import swept_teeth
from transplanter.gears.problem import load_problem
from transplanter.gears.rack_teeth import PitchTable
from transplanter.gears.synthesis import synthesize
from transplanter.gears.teeth import driven_table, driver_table
from transplanter.geometry.planar import DIAMOND_TURN, diamond_angle, modulo

from .ellipse_pair import GEARS, MODULE, driver_outline, ellipse_pair, swept_outline

#: Half the bisection's first bracket about the nearest sample, in modules.
BRACKET_MODULES = 0.1


def bisected_normal_coordinates(table: PitchTable, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(s, h) of each point by bisection on f(s) = (p - C(s)) . T(s), which falls through zero at the foot, in a
    bracket about the nearest sample, halved until it stops shrinking in floating point."""
    _, nearest = cKDTree(table.points[:-1]).query(points)
    low, high = table.arc[nearest] - BRACKET_MODULES * MODULE, table.arc[nearest] + BRACKET_MODULES * MODULE

    def condition(s):
        foot, tangent, _ = table.at(s)
        return np.sum((points - foot) * tangent, axis=1)

    assert (condition(low) > 0).all() and (condition(high) < 0).all()      # the bracket holds the foot
    for _ in range(200):
        middle = (low + high) / 2
        if not ((middle > low) & (middle < high)).any():
            break
        ahead = condition(middle) > 0
        low, high = np.where(ahead, middle, low), np.where(ahead, high, middle)
    s = (low + high) / 2
    foot, _, normal = table.at(s)
    return np.mod(s, table.perimeter), np.sum((points - foot) * normal, axis=1)


@pytest.mark.parametrize("gear", [0, 1])
def test_normal_coordinates_equal_bisection(gear):
    """Points from 2.5 modules below to 1.5 above both pitch curves of a 20-tooth ellipse pair, started up to half a
    module off their foot (and some over the curve's start, started just short of its end): s and h equal
    bisection's to 1e-9 mm, and the point is the foot plus h normals."""
    table = (driver_table, driven_table)[gear](ellipse_pair())
    generator = np.random.default_rng(3)
    s = np.r_[generator.uniform(0, table.perimeter, 20000), np.zeros(50)]
    foot, _, normal = table.at(s)
    points = foot + generator.uniform(-2.5 * MODULE, 1.5 * MODULE, (len(s), 1)) * normal
    start = np.r_[s[:-50] + generator.uniform(-0.5 * MODULE, 0.5 * MODULE, 20000),
                  np.full(50, np.nextafter(table.perimeter, 0))]
    arc, height = table.normal_coordinates(points, start, 1e-12 * MODULE)
    expected_arc, expected_height = bisected_normal_coordinates(table, points)
    wrapped = np.mod(arc - expected_arc + table.perimeter / 2, table.perimeter) - table.perimeter / 2
    assert np.abs(wrapped).max() < 1e-9
    assert np.abs(height - expected_height).max() < 1e-9
    foot, _, normal = table.at(arc)
    assert np.abs(foot + height[:, None] * normal - points).max() < 1e-9


@pytest.mark.parametrize("gear", GEARS)
def test_swept_outlines_equal_those_on_bisection(gear, monkeypatch):
    """On a 20-tooth ellipse pair of module 2, each swept outline equals the one built with every normal's foot
    found by bisection, to 1e-9 mm."""
    design = ellipse_pair()
    driver = driver_outline(design)
    converged = swept_outline(gear, design, driver)
    monkeypatch.setattr(PitchTable, "normal_coordinates",
                        lambda table, points, start, tolerance: bisected_normal_coordinates(table, points))
    assert np.abs(converged - swept_outline(gear, design, driver)).max() < 1e-9


def test_points_by_a_corner_get_a_foot_on_their_side_of_the_gear():
    """By the corners of the cusp example's composite driver (its pitch table turns by 23 deg within one sample
    interval there), points from 2.5 modules below to 1.5 above the curve, started where the ray through the
    centre meets it: each lies on its foot's normal to 1e-9 mm (inside a corner that may be either side's) and
    nearer it than the curve comes to its centre (a foot across the gear lies farther)."""
    problem = load_problem(Path(__file__).resolve().parents[2] / "examples" / "gear_cusp_composite.toml")
    table = driver_table(synthesize(dataclasses.replace(problem, module=None, teeth=None)).design)
    module = problem.module
    turn = np.abs(np.diff(np.unwrap(np.arctan2(table.tangents[:, 1], table.tangents[:, 0]))))
    corners = table.arc[np.flatnonzero(turn > np.radians(10))]
    generator = np.random.default_rng(7)
    s = np.repeat(corners, 4000) + generator.uniform(-module, module, 4000 * len(corners))
    foot, _, normal = table.at(s)
    points = foot + generator.uniform(-2.5 * module, 1.5 * module, (len(s), 1)) * normal
    start = swept_teeth._radial_arc(table)(swept_teeth._polar(points)[0])
    arc, height = table.normal_coordinates(points, start, 1e-12 * module)
    foot, _, normal = table.at(arc)
    assert np.abs(foot + height[:, None] * normal - points).max() < 1e-9
    assert (np.abs(height) < np.hypot(table.points[:, 0], table.points[:, 1]).min()).all()


def test_the_diamond_angle_orders_directions_as_the_polar_angle():
    """Round a turn of directions from -x (at any distance) the diamond angle rises by one turn, a quarter turn
    from each axis to the next; the radial arc's interpolation needs only that order."""
    angle = np.linspace(-np.pi, np.pi, 20001)[:-1]
    distance = np.random.default_rng(3).uniform(0.1, 100, angle.size)
    diamond = diamond_angle(distance * np.cos(angle), distance * np.sin(angle))
    rise = np.diff(np.r_[diamond, diamond[0] + DIAMOND_TURN] - diamond[0])
    assert (modulo(rise, DIAMOND_TURN) > 0).all() and np.isclose(modulo(rise, DIAMOND_TURN).sum(), DIAMOND_TURN)
    assert diamond_angle(np.array([1.0, 0.0, -1.0, 0.0]), np.array([0.0, 2.0, 0.0, -3.0])).tolist() == [0, 1, 2, -1]

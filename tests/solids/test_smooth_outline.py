"""A closed outline as smooth runs (``solids.smooth_outline``), against outlines whose true curves are known: a
sampled circle is one curve that holds the circle far closer than its chords, a sampled square four straight
curves meeting at its corners."""
import numpy as np

from transplanter.solids.smooth_outline import CORNER_DEGREES, smooth_runs


def _samples(curve, count: int = 2000) -> np.ndarray:
    return curve(np.linspace(curve.t[0], curve.t[-1], count))


def test_a_sampled_circle_is_one_curve_nearer_the_circle_than_its_chords():
    radius, count, within = 10.0, 720, 1e-6
    angle = np.linspace(0, 2 * np.pi, count, endpoint=False)
    outline = radius * np.column_stack([np.cos(angle), np.sin(angle)])
    [curve] = smooth_runs(outline, within)
    sagitta = radius * (1 - np.cos(np.pi / count))
    off_circle = np.abs(np.hypot(*_samples(curve, 20 * count).T) - radius)
    assert off_circle.max() <= within < sagitta / 10
    assert np.allclose(curve(curve.t[0]), outline[0]) and np.allclose(curve(curve.t[-1]), outline[0])


def test_a_sampled_square_is_four_straight_curves_from_corner_to_corner():
    side = np.linspace(0, 1, 50, endpoint=False)
    corners = np.array([[0, 0], [8, 0], [8, 8], [0, 8], [0, 0]], float)
    outline = np.vstack([a + np.outer(side, b - a) for a, b in zip(corners[:-1], corners[1:], strict=True)])
    curves = smooth_runs(outline, 1e-6)
    assert len(curves) == 4
    for curve, start, end in zip(curves, corners[:-1], corners[1:], strict=True):
        points = _samples(curve)
        assert np.allclose(points[[0, -1]], [start, end], atol=1e-9)
        along = (end - start) / 8
        assert np.abs((points - start) @ np.array([-along[1], along[0]])).max() < 1e-9


def test_a_turn_below_the_corner_angle_is_no_corner_unless_the_curve_cannot_hold_it():
    """Two straight sides meeting at a turn of half the corner angle: no corner by the angle, but no smooth curve
    holds both sides within the bound across the kink, so the run is split there."""
    turn = np.radians(CORNER_DEGREES / 2)
    first = np.outer(np.linspace(0, 5, 60), [1.0, 0.0])
    second = 5 * np.array([1.0, 0.0]) + np.outer(np.linspace(0, 5, 60)[1:], [np.cos(turn), np.sin(turn)])
    closing = np.outer(np.linspace(1, 0, 40, endpoint=False)[1:], second[-1])
    outline = np.vstack([first, second, closing])
    curves = smooth_runs(outline, 1e-6)
    ends = [tuple(np.round(curve(curve.t[0]), 9)) for curve in curves]
    assert (5.0, 0.0) in ends

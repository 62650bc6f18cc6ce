"""The shoelace sum of a closed outline: twice its area, signed by the way it runs, with or without its first point
repeated at the end; and the outline turned to run counterclockwise."""
import numpy as np

from transplanter.geometry.planar import counterclockwise, twice_signed_area


def test_a_rectangle_and_a_circle_give_twice_their_area_signed_by_their_sense():
    rectangle = np.array([[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0]])
    assert twice_signed_area(rectangle) == 12.0
    assert twice_signed_area(rectangle[::-1]) == -12.0
    assert twice_signed_area(np.vstack([rectangle, rectangle[:1]])) == 12.0         # the first point repeated
    t = np.linspace(0, 2 * np.pi, 2001)[:-1]
    circle = 5.0 * np.c_[np.cos(t), np.sin(t)] + [7.0, -3.0]
    assert abs(twice_signed_area(circle) - 2 * np.pi * 25.0) < 2 * np.pi * 25.0 * 1e-5


def test_counterclockwise_reverses_only_a_clockwise_outline():
    triangle = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]])
    assert counterclockwise(triangle) is triangle
    assert np.array_equal(counterclockwise(triangle[::-1]), triangle)

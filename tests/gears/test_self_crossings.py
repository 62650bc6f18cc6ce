"""Crossings of a closed polyline and the same polyline with its loops cut off at them."""
from __future__ import annotations

import numpy as np
import shapely

from transplanter.geometry.self_crossings import crossing_segments, without_loops


def _swallowtail() -> tuple[np.ndarray, np.ndarray]:
    """A square whose top edge, run from (1, 1) towards (0, 1), rises past x = 0.5 to (0.4, 1.2), steps back to
    (0.6, 1.2) and comes down to (0, 1): the lines y = 1 + (1 - x) / 3 and y = 1 + x / 3 cross at (0.5, 7/6).
    Returned with the square cut at that crossing."""
    ring = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.4, 1.2], [0.6, 1.2], [0.0, 1.0]])
    cut = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.5, 7 / 6], [0.0, 1.0]])
    return ring, cut


def test_a_loop_is_cut_at_its_crossing_wherever_the_ring_starts():
    ring, expected = _swallowtail()
    for shift in range(len(ring)):          # the loop inside the ring, and passing its first vertex
        rolled = np.roll(ring, shift, axis=0)
        assert len(crossing_segments(rolled)[0]) == 1
        cut = without_loops(rolled)
        assert len(cut) == len(expected) and shapely.is_simple(shapely.linearrings(cut))
        assert shapely.equals_exact(shapely.normalize(shapely.Polygon(cut)),
                                    shapely.normalize(shapely.Polygon(expected)), 1e-15)


def test_a_simple_ring_comes_back_unchanged():
    t = np.linspace(0, 2 * np.pi, 200, endpoint=False)
    circle = np.c_[np.cos(t), np.sin(t)]
    assert len(crossing_segments(circle)[0]) == 0
    assert without_loops(circle) is circle

"""The dyads move with the poses: a problem turned, moved and scaled as one rigid similarity gives the same dyads,
turned, moved and scaled (every search, bound and start works in the frame attached to the poses: their centroid,
their size, the body's direction in pose 1). The 7-pose least-squares example turned by 37 deg and moved by
(1234.5, -987.6) once gave a 548.5 mm dyad where the original gives 40.0 mm."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from transplanter import burmester
from transplanter.toml_fields import read_toml

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"


class Similarity:
    """Points turned by ``angle`` (rad) about ``about``, scaled by ``scale`` about it, then moved by ``shift``."""

    def __init__(self, angle: float, about, shift, scale: float = 1.0):
        self.angle, self.scale = angle, scale
        self.about, self.shift = np.asarray(about, float), np.asarray(shift, float)

    def _turned(self, points, angle):
        points = np.asarray(points, float)
        c, s = np.cos(angle), np.sin(angle)
        return np.stack([c * points[..., 0] - s * points[..., 1], s * points[..., 0] + c * points[..., 1]], -1)

    def forward(self, points):
        return self.scale * self._turned(np.asarray(points) - self.about, self.angle) + self.about + self.shift

    def back(self, points):
        return self._turned((np.asarray(points) - self.about - self.shift) / self.scale, -self.angle) + self.about

    def problem(self, data: dict) -> dict:
        """The problem dict moved: pose positions and directions, given pivots, the link's pivot, the radius."""
        data = json.loads(json.dumps(data))
        for row in data["poses"]:
            row["x"], row["y"] = self.forward([row["x"], row["y"]]).tolist()
            row["angle_deg"] += float(np.degrees(self.angle))
        for key in ("center_points", "circle_points"):
            if key in data.get("three_poses", {}):
                data["three_poses"][key] = self.forward(data["three_poses"][key]).tolist()
        if "relative" in data:
            data["relative"]["pivot"] = self.forward(data["relative"]["pivot"]).tolist()
        if "radius_mm" in data.get("search", {}):
            data["search"]["radius_mm"] *= self.scale
        return data


def _pivots(result) -> np.ndarray:
    return np.array([np.r_[dyad.center, dyad.circle] for dyad in result.dyads]).reshape(-1, 2, 2)


def _same_dyads_after_moving(name: str, move: Similarity, relative: float):
    data = read_toml(EXAMPLES / name)
    original = _pivots(burmester.synthesize(burmester.parse_problem(data)))
    moved = _pivots(burmester.synthesize(burmester.parse_problem(move.problem(data))))
    assert moved.shape == original.shape and len(original)
    size = np.abs(original).max()
    np.testing.assert_allclose(move.back(moved), original, rtol=0, atol=relative * size)


@pytest.mark.parametrize("name", ["burmester_3poses.toml", "burmester_4poses.toml", "burmester_5poses.toml",
                                  "burmester_7poses.toml", "burmester_relative.toml"])
def test_every_example_turned_and_moved_gives_its_dyads_turned_and_moved(name):
    _same_dyads_after_moving(name, Similarity(np.radians(37), (100, -50), (1234.5, -987.6), scale=2.5), 1e-9)


@settings(max_examples=8, deadline=None)
@given(angle=st.floats(-np.pi, np.pi), shift=st.tuples(st.floats(-1e4, 1e4), st.floats(-1e4, 1e4)),
       scale=st.floats(1e-2, 1e2), name=st.sampled_from(["burmester_3poses.toml", "burmester_5poses.toml",
                                                         "burmester_7poses.toml"]))
def test_any_similarity_moves_the_dyads_with_the_poses(angle, shift, scale, name):
    _same_dyads_after_moving(name, Similarity(angle, (0.0, 0.0), shift, scale), 1e-8)


@pytest.mark.parametrize("point", [(0.0, 0.0), (10.0, 20.0), (1234.5, -987.6)])
def test_poses_at_one_point_are_a_pure_rotation_with_its_one_dyad(point):
    """Four poses at one point, turned: the body turns about that point, and the dyad centred there is given,
    wherever the point is (it was found only at the origin: rounding of the poles grew with the coordinates)."""
    poses = [{"x": point[0], "y": point[1], "angle_deg": angle} for angle in (0.0, 30.0, 70.0, 100.0)]
    result = burmester.synthesize(burmester.parse_problem({"poses": poses}))
    assert result.method.startswith("pure rotation") and len(result.dyads) == 1
    np.testing.assert_allclose(result.dyads[0].center, point, rtol=0, atol=1e-12 * max(1.0, np.abs(point).max()))

"""A bore with its hub keyway, in the part's own frame (centre at the origin), millimetres."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.poses import rotate_about
from transplanter.shafts.keys import ParallelKey, parallel_key

#: Sides of the polygon ``outline`` gives for the bore's circle (solids, areas).
CIRCLE_SEGMENTS = 720


@dataclass(frozen=True)
class KeyedBore:
    """A bore of ``diameter`` mm with a DIN 6885-1 keyway (``key``) centred on ``direction`` (rad, counterclockwise
    from +x in the part's frame)."""

    diameter: float
    key: ParallelKey
    direction: float = 0.0

    @classmethod
    def for_shaft(cls, diameter: float, direction: float = 0.0, field: str = "shafts") -> KeyedBore:
        return cls(float(diameter), parallel_key(diameter, field), float(direction))

    @property
    def radius(self) -> float:
        return self.diameter / 2

    @property
    def reach(self) -> float:
        """Distance from the centre to the keyway's bottom in the hub, d/2 + t2 (mm)."""
        return self.radius + self.key.hub_depth

    @property
    def half_angle(self) -> float:
        """Half the angle the keyway cuts out of the bore's circle (rad)."""
        return float(np.arcsin(self.key.width / self.diameter))

    def keyway(self) -> np.ndarray:
        """The keyway's three sides (4, 2) from the bore's circle out and back, counterclockwise."""
        half, inner = self.key.width / 2, self.radius * np.cos(self.half_angle)
        local = np.array([[inner, -half], [self.reach, -half], [self.reach, half], [inner, half]])
        return rotate_about(local, (0.0, 0.0), self.direction)

    def outline(self, segments: int = CIRCLE_SEGMENTS) -> np.ndarray:
        """The hole's closed outline (N, 2): the keyway, then the bore's circle back round to it."""
        arc = np.linspace(self.half_angle, 2 * np.pi - self.half_angle, segments)[1:-1]
        circle = self.radius * np.c_[np.cos(arc), np.sin(arc)]
        return np.vstack([self.keyway(), rotate_about(circle, (0.0, 0.0), self.direction)])


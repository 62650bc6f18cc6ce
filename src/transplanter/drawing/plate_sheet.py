"""A flat link part on a sheet: holes at hinge or shaft centres, an outline round them, the centre distances as
aligned dimensions and each hole's diameter, in the part's own frame (the first hole at the origin, the second
on +x), millimetres."""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import shapely

from transplanter.drawing.sheet import Sheet, TitleBlock
from transplanter.geometry.poses import rotate_about

#: The boss round a hole reaches this many hole diameters past the hole's edge.
BOSS_DIAMETERS = 0.5
#: Quadrant segments of the round ends of the outline (shapely's buffer).
ROUND_SEGMENTS = 32


@dataclass(frozen=True)
class Hole:
    """A hole of ``diameter`` mm at ``center`` (2,) mm; diameter 0 for a point of the part that is not a hole
    (the push plate's P), which the outline rounds at ``boss`` mm."""

    label: str
    center: np.ndarray
    diameter: float
    boss: float = 0.0

    @property
    def boss_radius(self) -> float:
        return self.diameter / 2 + (BOSS_DIAMETERS * self.diameter if self.diameter else self.boss)


@dataclass(frozen=True)
class PlatePart:
    """A link plate: its holes, the pairs of hole labels whose centre distances are dimensioned, the title."""

    name: str
    holes: tuple[Hole, ...]
    dimensioned: tuple[tuple[str, str], ...]
    title: TitleBlock

    @property
    def centers(self) -> dict[str, np.ndarray]:
        return {hole.label: hole.center for hole in self.holes}

    def outline(self) -> np.ndarray:
        """The closed outline (N, 2): the convex hull of the bosses round every hole, counterclockwise."""
        bosses = [shapely.Point(*hole.center).buffer(hole.boss_radius, quad_segs=ROUND_SEGMENTS)
                  for hole in self.holes]
        hull = shapely.convex_hull(shapely.union_all(bosses))
        return shapely.get_coordinates(shapely.get_exterior_ring(shapely.normalize(hull)))[:-1][::-1]

    def placed(self, first, second) -> Callable[[np.ndarray], np.ndarray]:
        """The rigid motion taking the part's frame to where its first two holes are ``first`` and ``second``:
        a function of points (N, 2)."""
        first, second = np.asarray(first, float), np.asarray(second, float)
        along = second - first
        local = self.holes[1].center - self.holes[0].center
        turn = np.arctan2(along[1], along[0]) - np.arctan2(local[1], local[0])

        def motion(points: np.ndarray) -> np.ndarray:
            return rotate_about(np.asarray(points, float) - self.holes[0].center, (0.0, 0.0), turn) + first

        return motion


def outside_offset(outline: np.ndarray, first, second, margin: float) -> float:
    """The offset (mm, positive to the left of ``first`` -> ``second``) that puts the dimension line of that
    distance ``margin`` mm clear of the ``outline`` (N, 2), on the side away from the plate's centroid (the
    left one when the centroid is on the line, as for a two-hole link)."""
    first = np.asarray(first, float)
    along = np.asarray(second, float) - first
    left = np.array([-along[1], along[0]]) / np.hypot(*along)
    reach = (outline - first) @ left
    centroid_side = float((shapely.get_coordinates(shapely.Polygon(outline).centroid)[0] - first) @ left)
    if centroid_side > 1e-9 * float(np.ptp(reach)):
        return float(reach.min()) - margin
    return float(reach.max()) + margin


def plate_sheet(part: PlatePart) -> Sheet:
    """Outline, holes, centre crosses and lines, labels, centre distances and hole diameters, the title block."""
    sheet = Sheet()
    sheet.polyline(part.outline(), "OUTLINE", close=True)
    centers = part.centers
    for hole in part.holes:
        if hole.diameter:
            sheet.circle(hole.center, hole.diameter / 2, "BORE")
        sheet.center_cross(hole.center, 2 * hole.boss_radius)
    outline = part.outline()
    margin = max(hole.boss_radius for hole in part.holes)
    for first, second in part.dimensioned:
        sheet.line(centers[first], centers[second], "CENTERLINES")
        sheet.aligned_dimension(centers[first], centers[second],
                                outside_offset(outline, centers[first], centers[second], margin))
    for hole in part.holes:
        sheet.text(hole.label, hole.center + hole.boss_radius)
        if hole.diameter:
            sheet.diameter_dimension(hole.center, hole.diameter / 2, 225.0)
    sheet.title_block(part.title)
    return sheet

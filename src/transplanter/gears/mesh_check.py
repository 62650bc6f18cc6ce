"""Two toothed gears turned by their designed motion: overlap, contact gap and transmission error.

The driver sits at the origin turned clockwise by phi1, the driven gear at (a, 0) turned
counterclockwise by phi2(phi1) from the pitch-curve design (``pair.driven_angle``), as
``design_pair`` lays a pair out. Driver angles are spread evenly in arc length, several per
tooth, over one driven turn. At each position every outline vertex near the pitch point is
measured against the other outline, which stays in its own frame so that its segments are filed
once, in a grid of square cells (a point's cell lists every segment within the search cap):

- d, the signed distance to the nearest segment of the other outline (exact point-to-segment
  distance; the sign from shapely's point-in-polygon test, negative inside). The position's
  clearance is the smallest d: below zero it is an overlap depth, above zero the teeth do not touch;
- turning the driven gear by delta changes d by delta sigma to first order, sigma being the
  outward normal of the nearest segment dotted with the vertex's velocity per unit turn. The
  driven gear turned back by the largest d / sigma over sigma < 0 rests on the driving flanks:
  that turn is the transmission error against the design (positive ahead). Turned forward by
  the smallest d / sigma over sigma > 0 it meets the coast flanks; the two turns bound the play.
  Vertices whose normal is within ``RADIAL_NORMAL`` of radial (tips, roots) cannot meet by
  turning and are left out of both.

Gears cut by one rack, or a driven gear swept by its driver's teeth, are conjugate with no
backlash: they touch at every position to the outlines' resolution. Tolerances are fractions
of the module.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.geometry.outline_thinning import thinned
from transplanter.geometry.planar import counterclockwise
from transplanter.geometry.poses import rotate_about

ORIGIN = (0.0, 0.0)

#: Positions per tooth along the driver's pitch curve.
SAMPLES_PER_TOOTH = 8
#: Vertices within this many circular pitches of the pitch point (along each pitch curve) are measured.
REACH_PITCHES = 1.5
#: Measured vertices are thinned to about this spacing along their outline (modules); the other outline
#: keeps its segments (simplified as below).
SPACING_MODULES = 0.05
#: The measured-against outline is simplified (Douglas-Peucker) within this many modules.
SIMPLIFY_MODULES = 5e-4
#: Distances are searched up to this many modules; a vertex farther from the other outline counts as this far.
CAP_MODULES = 0.25
#: |sigma| below this fraction of the vertex's lever about the driven centre: a normal too near radial.
RADIAL_NORMAL = 0.3
#: Largest overlap, contact gap and transmission error (as arc on the driven pitch curve) allowed, in modules.
OVERLAP_MODULES, GAP_MODULES, ERROR_MODULES = 0.005, 0.01, 0.005


class _SegmentGrid:
    """Segments of a closed outline filed under every square cell of side ``cap`` that their box, grown
    by ``cap``, covers: a point's own cell then lists every segment nearer to it than ``cap``."""

    def __init__(self, points: np.ndarray, cap: float):
        self.starts, self.ends, self.cap = points, np.roll(points, -1, axis=0), cap
        low = np.floor((np.minimum(self.starts, self.ends) - cap) / cap).astype(np.int64)
        high = np.floor((np.maximum(self.starts, self.ends) + cap) / cap).astype(np.int64)
        span = high - low + 1
        count = span[:, 0] * span[:, 1]
        segment = np.repeat(np.arange(len(points)), count)
        local = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        cells = low[segment] + np.c_[local % span[segment, 0], local // span[segment, 0]]
        key = self._key(cells)
        order = np.argsort(key, kind="stable")
        self.keys, first, self.counts = np.unique(key[order], return_index=True, return_counts=True)
        self.first, self.segments = first, segment[order]

    @staticmethod
    def _key(cells: np.ndarray) -> np.ndarray:
        return (cells[:, 0] << 32) + cells[:, 1]

    def nearest(self, points: np.ndarray, chunk: int = 8192) -> tuple[np.ndarray, np.ndarray]:
        """Distance (capped) from each point to the outline and the index of the nearest segment (-1 beyond the cap).
        Points are taken in chunks of like count of listed segments (then by cell), so a chunk's table, as wide as
        its largest count, holds few unlisted places: by cell alone it held 3-4 times the listed ones."""
        distance, nearest = np.full(len(points), self.cap), np.full(len(points), -1)
        keys = self._key(np.floor(points / self.cap).astype(np.int64))
        cells = np.clip(np.searchsorted(self.keys, keys), 0, len(self.keys) - 1)
        counts = np.where(self.keys[cells] == keys, self.counts[cells], 0)
        by_count = np.lexsort((keys, counts))
        ax, ay = self.starts.T
        ex, ey = (self.ends - self.starts).T
        inverse = 1 / np.maximum(ex * ex + ey * ey, 1e-300)
        for lo in range(int(np.searchsorted(counts[by_count], 1)), len(points), chunk):
            index = by_count[lo:lo + chunk]
            count = counts[index]
            column = np.arange(int(count[-1]))
            listed = column < count[:, None]
            candidate = self.segments[np.where(listed, self.first[cells[index]][:, None] + column, 0)]
            ox, oy = points[index, :1] - ax[candidate], points[index, 1:] - ay[candidate]
            cx, cy = ex[candidate], ey[candidate]
            t = np.clip((ox * cx + oy * cy) * inverse[candidate], 0.0, 1.0)
            ox -= t * cx
            oy -= t * cy
            squared = np.where(listed, ox * ox + oy * oy, np.inf)
            best = np.argmin(squared, axis=1)
            rows = np.arange(len(index))
            value = np.sqrt(squared[rows, best])
            hit = value < self.cap
            distance[index[hit]] = value[hit]
            nearest[index[hit]] = candidate[rows, best][hit]
        return distance, nearest


class _Outline:
    """A closed outline in its own frame: its segments filed by cell with their outward normals, and the
    vertices to measure (thinned to ``spacing``) sorted by polar angle."""

    def __init__(self, outline: np.ndarray, spacing: float, simplify: float, cap: float):
        points = counterclockwise(np.asarray(outline, float))
        simple = thinned(points, simplify)
        tangent = np.roll(simple, -1, axis=0) - simple
        self.normals = np.c_[tangent[:, 1], -tangent[:, 0]] / np.linalg.norm(tangent, axis=1, keepdims=True)
        self.grid = _SegmentGrid(simple, cap)
        self.polygon = shapely.polygons(simple)
        shapely.prepare(self.polygon)
        tangent = np.roll(points, -1, axis=0) - points
        length = np.linalg.norm(tangent, axis=1)
        arc = np.r_[0.0, np.cumsum(length[:-1])]
        kept = points[np.r_[True, np.diff(np.floor(arc / spacing)) > 0]]
        angle = np.arctan2(kept[:, 1], kept[:, 0])
        order = np.argsort(angle)
        self.vertices, self.sorted_angle = kept[order], angle[order]

    def near(self, directions: np.ndarray, half_width: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vertices whose polar angle lies within ``half_width`` of each direction: (position, vertex) index pairs."""
        n = len(self.sorted_angle)
        wrapped = np.mod(directions + np.pi, 2 * np.pi) - np.pi
        start = np.searchsorted(self.sorted_angle, wrapped - half_width)
        stop = np.searchsorted(self.sorted_angle, wrapped + half_width)
        width = int(np.max(np.mod(stop - start, n))) + 2
        index = (start[:, None] + np.arange(-1, width)) % n
        offset = np.mod(self.sorted_angle[index] - wrapped[:, None] + np.pi, 2 * np.pi) - np.pi
        position, column = np.nonzero(np.abs(offset) <= half_width[:, None])
        return position, index[position, column]

    def signed_distance(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Signed distance (mm, negative inside, magnitude at most the cap) of points (M, 2) to the outline,
        and the outward normal of the nearest segment (zero beyond the cap)."""
        distance, segment = self.grid.nearest(points)
        normal = np.where((segment >= 0)[:, None], self.normals[segment], 0.0)
        inside = shapely.contains_xy(self.polygon, points[:, 0], points[:, 1])
        return np.where(inside, -distance, distance), normal


def _cross_z(vectors: np.ndarray) -> np.ndarray:
    """k x v for vectors (..., 2): the velocity of a point at v per unit counterclockwise turn."""
    return np.stack([-vectors[..., 1], vectors[..., 0]], -1)


@dataclass(frozen=True)
class MeshCheck:
    """A toothed pair over one driven turn, position by position (mm, radians)."""

    module: float
    driver_angle: np.ndarray          # phi1 at each position
    clearance: np.ndarray             # smallest signed distance between the outlines (mm; < 0 overlap)
    transmission_error: np.ndarray    # driven turn to rest on the driving flanks, against the design (rad)
    play: np.ndarray                  # driven turn from driving to coast flanks (rad)
    driven_pitch_radius: np.ndarray   # driven pitch radius at the contact (mm), to express angles as arc

    @property
    def max_overlap_mm(self) -> float:
        return float(max(0.0, -self.clearance.min()))

    @property
    def min_clearance_mm(self) -> float:
        """Smallest clearance over the turn (negative: the deepest overlap)."""
        return float(self.clearance.min())

    @property
    def max_contact_gap_mm(self) -> float:
        """Largest clearance at any position: how far apart the teeth are where they touch least."""
        return float(max(0.0, self.clearance.max()))

    @property
    def max_transmission_error_rad(self) -> float:
        return float(np.abs(self.transmission_error).max())

    @property
    def max_transmission_error_mm(self) -> float:
        """Transmission error as arc length on the driven pitch curve."""
        return float(np.abs(self.transmission_error * self.driven_pitch_radius).max())

    @property
    def failures(self) -> list[str]:
        """What exceeds its tolerance, with the numbers; empty when the pair meshes."""
        m = self.module
        found = []
        if self.max_overlap_mm > OVERLAP_MODULES * m:
            k = int(np.argmin(self.clearance))
            found.append(f"the teeth overlap by {self.max_overlap_mm:.4f} mm at driver angle "
                         f"{np.degrees(self.driver_angle[k]):.2f} deg (tolerance {OVERLAP_MODULES * m:.4f} mm)")
        if self.max_contact_gap_mm > GAP_MODULES * m:
            k = int(np.argmax(self.clearance))
            found.append(f"the teeth do not touch at driver angle {np.degrees(self.driver_angle[k]):.2f} deg: "
                         f"gap {self.max_contact_gap_mm:.4f} mm (backlash allowed {GAP_MODULES * m:.4f} mm)")
        if self.max_transmission_error_mm > ERROR_MODULES * m:
            k = int(np.argmax(np.abs(self.transmission_error * self.driven_pitch_radius)))
            found.append(f"transmission error {np.degrees(self.transmission_error[k]):.4f} deg "
                         f"({self.max_transmission_error_mm:.4f} mm of driven pitch arc) at driver angle "
                         f"{np.degrees(self.driver_angle[k]):.2f} deg (tolerance {ERROR_MODULES * m:.4f} mm)")
        return found

    @property
    def passed(self) -> bool:
        return not self.failures


def check_mesh(design: GearPairDesign, outlines: tuple[np.ndarray, np.ndarray], module: float,
               samples_per_tooth: int = SAMPLES_PER_TOOTH) -> MeshCheck:
    """Turn the toothed pair by its designed motion and measure it (module docstring).

    Parameters
    ----------
    design : GearPairDesign
        The pitch curves and their motion.
    outlines : (ndarray, ndarray)
        Driver and driven tooth outlines (N, 2) in their own frames (mm), as ``generate_teeth`` gives them.
    module : float
        mm; sets the reach and the tolerances.
    samples_per_tooth : int
        Positions per tooth of the driver.
    """
    n1, n2 = design.orders
    spacing, simplify, cap = (share * module for share in (SPACING_MODULES, SIMPLIFY_MODULES, CAP_MODULES))
    driver, driven = (_Outline(o, spacing, simplify, cap) for o in outlines)
    perimeter = design.perimeters[0] * n2 / n1                        # arc run off during one driven turn
    count = int(round(perimeter / (np.pi * module))) * samples_per_tooth
    arc = np.arange(count) * perimeter / count
    phi1 = (np.interp(np.mod(arc, design.perimeters[0]), design.arc, design.phi1)
            + 2 * np.pi * np.floor(arc / design.perimeters[0]))
    phi2 = driven_angle(design, phi1)
    a = design.center_distance
    r1 = np.interp(np.mod(phi1, 2 * np.pi), design.phi1, design.radius[0])
    reach = REACH_PITCHES * np.pi * module
    # the contact lies at polar angle phi1 in the driver's frame and pi - phi2 in the driven gear's
    at1, k1 = driver.near(phi1, np.minimum(reach / r1, np.pi))
    at2, k2 = driven.near(np.pi - phi2, np.minimum(reach / (a - r1), np.pi))

    # driver vertices in the driven gear's frame, which turns back relative to them as the driven gear turns
    p = rotate_about(rotate_about(driver.vertices[k1], ORIGIN, -phi1[at1]) - [a, 0.0], ORIGIN, -phi2[at1])
    d1, n_1 = driven.signed_distance(p)
    sigma1, lever1 = np.sum(n_1 * _cross_z(p), axis=1), np.linalg.norm(p, axis=1)
    # driven vertices in the driver's frame; turning the driven gear moves them by k x (e - C) in the world
    e = rotate_about(driven.vertices[k2], ORIGIN, phi2[at2])
    q = rotate_about(e + [a, 0.0], ORIGIN, phi1[at2])
    d2, n_2 = driver.signed_distance(q)
    sigma2 = -np.sum(n_2 * rotate_about(_cross_z(e), ORIGIN, phi1[at2]), axis=1)
    lever2 = np.linalg.norm(e, axis=1)

    at, d, sigma, lever = np.r_[at1, at2], np.r_[d1, d2], np.r_[sigma1, sigma2], np.r_[lever1, lever2]
    clearance = np.full(count, cap)
    np.minimum.at(clearance, at, d)
    turning = np.abs(sigma) >= RADIAL_NORMAL * lever
    turn = np.where(turning, d / np.where(turning, sigma, 1.0), 0.0)
    limit = cap / (a - r1)                       # a turn no nearer contact than the cap can resolve
    back, ahead = -limit.copy(), limit.copy()
    np.maximum.at(back, at[turning & (sigma < 0)], turn[turning & (sigma < 0)])
    np.minimum.at(ahead, at[turning & (sigma > 0)], turn[turning & (sigma > 0)])
    return MeshCheck(module, phi1, clearance, back, ahead - back, a - r1)

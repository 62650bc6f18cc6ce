"""How far a shaper-cut outline lies from the closed form of the variable involute of the cusp-pitch-curve
paper (eq 1-6).

``derivations/cusp.py`` re-derives the paper's construction: the flank point a pinion cutter generates
does not depend on the cutter's size, so every pinion cutter, and a rack, generates the same curve
(``rack_teeth.flank_points``), as long as the contact stays on the cutter's involute (``shaper_reach``).
The package cuts the smooth stretches by the numerical envelope of ``swept_teeth`` instead, which also
gives the root fillets and any undercut; this compares the two, flank by flank, on the points of the
closed form below the tip whose contact stays on the flank's own segment (a cutter cannot roll round a
corner):

- ``largest_mm``: the largest distance from the closed form, where the cutter's involute generates it,
  to the cut outline. What the envelope adds: its bins (each keeps the lowest height over 0.002 module of
  pitch arc, so a sloped flank moves by up to half a bin: 0.002 mm at module 2), the chords between the
  cutter's positions, or a flank that another position cut away (undercut).
- ``tip_trim_mm``: the largest distance past the reach's outward end, below the tip, where the cutter's
  radial root trims the tooth's top (on a straight stretch above r_j sin^2 alpha).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import shapely

from transplanter._generated.cusp import shaper_reach
from transplanter.gears.pinion_cutter import shaper_cutter_radii
from transplanter.gears.rack_teeth import ADDENDUM, PitchTable, flank_points
from transplanter.generated import numpy_twin

_REACH = numpy_twin(shaper_reach)
#: Points of the closed form per flank, spread over q = -side (s_f - s) from the reach's inward end to the tip.
POINTS_PER_FLANK = 60


@dataclass(frozen=True)
class InvoluteDeviation:
    """The cut outline against the closed-form variable involute (module docstring); arcs in mm."""

    largest_mm: float
    where_arc_mm: float              # pitch arc of the flank's pitch point where it is largest
    tip_trim_mm: float
    flanks_compared: int
    points_compared: int


def involute_deviation(table: PitchTable, outline: np.ndarray, flanks: np.ndarray, sides: np.ndarray,
                       above_pitch: np.ndarray, corners: np.ndarray, module: float, alpha: float,
                       cutter_teeth: int) -> InvoluteDeviation:
    """Compare ``outline`` with the closed form on the flanks with pitch points at arcs ``flanks`` (mm) and sides
    ``sides`` (+1: a tooth's low-arc flank), above the pitch curve only where ``above_pitch``; no contact may pass
    a corner at the arcs ``corners``."""
    cutter, tip, lowest = shaper_cutter_radii(module, alpha, cutter_teeth)
    (low, high), = _REACH([alpha], [cutter], [tip], [lowest])
    low, high = float(low), float(high)
    tip_height = ADDENDUM * module
    q = np.linspace(low, 1.5 * tip_height / (np.sin(alpha) * np.cos(alpha)), POINTS_PER_FLANK)
    flanks, sides = np.asarray(flanks, float)[:, None], np.asarray(sides, float)[:, None]
    points = flank_points(table, flanks, sides, alpha, -sides * q)
    pitch_curve = shapely.Polygon(table.points)
    flat = points.reshape(-1, 2)
    height = shapely.distance(pitch_curve.exterior, shapely.points(flat))
    inside = shapely.contains_xy(pitch_curve, flat[:, 0], flat[:, 1])
    height = np.where(inside, -height, height).reshape(points.shape[:2])
    perimeter = table.perimeter
    passes = np.zeros(points.shape[:2], bool)
    for corner in corners:      # a corner strictly between the flank's pitch point and the contact
        ahead = np.mod(corner - flanks, perimeter)
        passes |= np.where(sides * q > 0, ahead < sides * q, np.mod(flanks - corner, perimeter) < -sides * q)
    usable = (height <= tip_height) & ~passes & (np.asarray(above_pitch)[:, None] | (height <= 0))
    within = usable & (q <= high)
    beyond = usable & (q > high)
    distance = _distances(outline, points.reshape(-1, 2)).reshape(points.shape[:2])
    worst = np.unravel_index(np.argmax(np.where(within, distance, -1.0)), distance.shape)
    return InvoluteDeviation(float(distance[within].max(initial=0.0)), float(flanks[worst[0], 0]),
                             float(distance[beyond].max(initial=0.0)), int(within.any(axis=1).sum()), int(within.sum()))


def _distances(outline: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Distance (mm) from each point to the closed polyline ``outline``, through a tree of its edges."""
    edges = np.asarray(shapely.linestrings(np.stack([outline, np.roll(outline, -1, axis=0)], axis=1)))
    tree = shapely.STRtree(edges)
    (_, _), distance = tree.query_nearest(shapely.points(points), return_distance=True, all_matches=False)
    return distance

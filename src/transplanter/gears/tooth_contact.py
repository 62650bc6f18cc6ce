"""Contact ratio of a toothed pair measured along the whole cycle, tooth by tooth and flank by flank.

The pair is turned by its designed motion, positions ``SAMPLES_PER_PITCH`` per pitch of driver
pitch arc. At each position the driver's outline points near the contact are put in the driven
gear's frame; a point within ``TOUCH_MODULES`` of the driven outline touches. Tip points (within
``TIP_MODULES`` of the addendum) are left out: the driven root was carved by them and they graze it
whatever the flanks do. Each touching point
belongs to a driver tooth (the tooth whose pitch-curve span, from one space centre to the next,
holds the foot of the point on the pitch curve) and to its low-arc or high-arc flank; one flank
side drives when the driver turns one way, the other when it turns back (the cusp-pitch-curve paper, section 3.2: the
contact ratio of a cusp gear depends on the direction). A tooth's contact ratio on a side is the
pitch arc rolled while that flank touches over the tooth's own pitch (the mean spacing to its neighbours'
centres); positions where no flank of a side touches are listed too (there the next pair has not taken over).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
import shapely
from scipy.spatial import cKDTree

from transplanter.gears.mesh_check import GAP_MODULES
from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.gears.rack_teeth import ADDENDUM

SAMPLES_PER_PITCH = 24
#: A driver point this close to the driven outline (modules) touches it: the backlash ``mesh_check`` allows.
TOUCH_MODULES = GAP_MODULES
#: Driver points within this many pitches of the contact, about this many modules apart, are measured.
REACH_PITCHES, SPACING_MODULES = 1.5, 0.01
#: Driver points this close (modules) to the tip height are the tip, not a flank: they are not measured.
TIP_MODULES = 0.05


class LeastContact(NamedTuple):
    """Where a contact ratio is smallest: the driver tooth (index), its centre's polar angle (deg), the flank side."""

    tooth: int
    phi_deg: float
    flank: str


@dataclass(frozen=True)
class ContactRatio:
    """Per driver tooth and flank side: contact ratio and the tooth's pitch-arc centre (mm)."""

    tooth_centers: np.ndarray        # (T,) pitch arc of each tooth's centre (mm)
    ratios: np.ndarray               # (2, T): low-arc flanks, high-arc flanks
    tooth_angles_deg: np.ndarray     # (T,) driver polar angle of each tooth's centre
    uncovered_deg: tuple[np.ndarray, np.ndarray]   # driver angles where no flank of a side touches

    @property
    def minimum(self) -> float:
        return float(np.nanmin(self.ratios))

    def where(self) -> LeastContact:
        side, tooth = np.unravel_index(int(np.nanargmin(self.ratios)), self.ratios.shape)
        return LeastContact(int(tooth), float(self.tooth_angles_deg[tooth]), ("low-arc", "high-arc")[side])


def _densified(outline: np.ndarray, spacing: float) -> np.ndarray:
    """Points along a closed outline no farther than ``spacing`` apart."""
    ends = np.roll(outline, -1, axis=0)
    counts = np.maximum(1, np.ceil(np.linalg.norm(ends - outline, axis=1) / spacing).astype(int))
    share = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    index = np.repeat(np.arange(len(outline)), counts)
    return outline[index] + (share / counts[index])[:, None] * (ends - outline)[index]


def measure_contact_ratio(design: GearPairDesign, outlines: tuple[np.ndarray, np.ndarray], module: float,
                          space_centers: np.ndarray) -> ContactRatio:
    """Contact ratio of every driver tooth on both flank sides over one driven turn (module docstring).

    ``space_centers`` are the pitch arcs (mm, ascending, within one turn) of the driver's tooth-space centres;
    tooth i lies between space centres i and i + 1.
    """
    pitch, perimeter = np.pi * module, design.perimeters[0]
    n1, n2 = design.orders
    driver = _densified(outlines[0], SPACING_MODULES * module)
    driver = driver[np.r_[0, np.flatnonzero(np.diff(np.floor(np.r_[0.0, np.cumsum(np.linalg.norm(
        np.diff(driver, axis=0), axis=1))] / (SPACING_MODULES * module)))) + 1]]
    # the tips graze the mate's root, which they carved: only flanks count
    height = shapely.distance(shapely.Polygon(design.points[0]), shapely.points(driver))
    driver = driver[height < (ADDENDUM - TIP_MODULES) * module]
    foot = cKDTree(design.points[0][:-1]).query(driver)[1]
    arc = design.arc[foot]                                           # pitch arc of each driver point's foot
    driven = cKDTree(_densified(outlines[1], TOUCH_MODULES * module / 2))
    edges = np.r_[space_centers, space_centers[0] + perimeter]
    tooth = np.mod(np.searchsorted(edges, np.where(arc < space_centers[0], arc + perimeter, arc)) - 1,
                   len(space_centers))
    unwrapped = (edges[:-1] + edges[1:]) / 2
    centers = np.mod(unwrapped, perimeter)
    offset = np.mod(arc - centers[tooth] + perimeter / 2, perimeter) - perimeter / 2
    side = (offset > 0).astype(int)
    step = pitch / SAMPLES_PER_PITCH
    rolled = np.arange(0.0, perimeter * n2 / n1, step)
    phi1 = np.interp(np.mod(rolled, perimeter), design.arc, design.phi1) + 2 * np.pi * np.floor(rolled / perimeter)
    phi2 = driven_angle(design, phi1)
    touching = np.zeros((2, len(space_centers), len(rolled)), bool)
    for k, (s, a, b) in enumerate(zip(np.mod(rolled, perimeter), phi1, phi2, strict=True)):
        near = np.flatnonzero(np.abs(np.mod(arc - s + perimeter / 2, perimeter) - perimeter / 2)
                              <= REACH_PITCHES * pitch)
        c1, s1, c2, s2 = np.cos(a), np.sin(a), np.cos(b), np.sin(b)
        world = driver[near] @ np.array([[c1, -s1], [s1, c1]]) - [design.center_distance, 0.0]
        local = world @ np.array([[c2, -s2], [s2, c2]])
        hit = near[driven.query(local, distance_upper_bound=TOUCH_MODULES * module)[0] <= TOUCH_MODULES * module]
        touching[side[hit], tooth[hit], k] = True
    spacing = np.diff(np.r_[unwrapped[-1] - perimeter, unwrapped, unwrapped[0] + perimeter])
    local_pitch = (spacing[:-1] + spacing[1:]) / 2
    ratios = touching.sum(axis=2) * step * n1 / n2 / local_pitch      # rolled arc in contact per driver turn
    phi = np.interp(centers, design.arc, design.phi1)
    uncovered = tuple(np.degrees(phi1[~touching[flank].any(axis=0)]) for flank in (0, 1))
    return ContactRatio(centers, ratios, np.degrees(phi), uncovered)

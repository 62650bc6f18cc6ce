"""Tooth profiles of both gears of a designed pair, with undercut, concavity and contact-ratio checks."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.gear_pair import GearPairDesign
from transplanter.rack_teeth import ADDENDUM, ToothProfile, pitch_table, rack_profile


def _unit(vectors):
    return vectors / np.linalg.norm(vectors, axis=1, keepdims=True)


def driver_table(design: GearPairDesign):
    r, slope, _ = design.driver.evaluate(design.phi1)
    c, s = np.cos(design.phi1), np.sin(design.phi1)
    tangents = _unit(np.c_[slope * c - r * s, slope * s + r * c])
    return pitch_table(design.points[0], design.arc, tangents)


def driven_table(design: GearPairDesign):
    """The driven curve over its own full turn: n2/n1 driver turns, tiled by periodicity."""
    n1, n2 = design.orders
    turn, perimeter = 2 * np.pi * n1 / n2, design.perimeters[0]
    tiles = int(np.ceil(n2 / n1))
    phi2 = np.concatenate([design.phi2[:-1] + k * turn for k in range(tiles)] + [[tiles * turn]])
    arc = np.concatenate([design.arc[:-1] + k * perimeter for k in range(tiles)] + [[tiles * perimeter]])
    r2 = np.r_[np.tile(design.radius[1][:-1], tiles), design.radius[1][0]]
    slope = np.r_[np.tile(design.driven_slope[:-1], tiles), design.driven_slope[0]]
    keep = phi2 < 2 * np.pi - 1e-12
    phi2, arc, r2, slope = phi2[keep], arc[keep], r2[keep], slope[keep]
    phi2, arc = np.r_[phi2, 2 * np.pi], np.r_[arc, design.perimeters[1]]
    r2, slope = np.r_[r2, r2[0]], np.r_[slope, slope[0]]
    c, s = np.cos(phi2), np.sin(phi2)
    points = r2[:, None] * np.c_[-c, s]
    tangents = _unit(np.c_[-slope * c + r2 * s, slope * s + r2 * c])
    return pitch_table(points, arc, tangents)


@dataclass(frozen=True)
class PairTeeth:
    profiles: tuple[ToothProfile, ToothProfile]
    contact_ratio: tuple[float, float]   # min, max of the local estimate along one driver turn
    self_intersections: tuple[int, int]


def local_contact_ratio(rho1, rho2, module: float, alpha: float) -> np.ndarray:
    """Contact ratio of the spur pair that osculates the pitch curves at the contact point (convex parts)."""
    h = ADDENDUM * module

    def approach(rho):
        return np.sqrt((rho + h) ** 2 - (rho * np.cos(alpha)) ** 2) - rho * np.sin(alpha)

    return (approach(rho1) + approach(rho2)) / (np.pi * module * np.cos(alpha))


def _side(p, q, r):
    return np.sign((q[..., 0] - p[..., 0]) * (r[..., 1] - p[..., 1]) - (q[..., 1] - p[..., 1]) * (r[..., 0] - p[..., 0]))


def self_intersections(outline: np.ndarray, window: int = 400) -> int:
    """Proper crossings between non-adjacent segments of a closed outline.

    Segments are sorted by the polar angle of their midpoints; each is tested against the
    next ``window`` in that order (crossing segments of a star-shaped outline are neighbours
    in angle), boxes first, then the orientation test.
    """
    a, b = outline, np.roll(outline, -1, axis=0)
    n = len(a)
    order = np.argsort(np.arctan2(*((a + b) / 2)[:, ::-1].T))
    i = np.repeat(order, min(window, n) - 1)
    j = order[(np.arange(n)[:, None] + np.arange(1, min(window, n))[None, :]).ravel() % n]
    low, high = np.minimum(a, b), np.maximum(a, b)
    overlap = np.all((low[i] <= high[j]) & (low[j] <= high[i]), axis=1)
    gap = np.abs(i - j)
    i, j = i[overlap & (gap > 1) & (gap < n - 1)], j[overlap & (gap > 1) & (gap < n - 1)]
    crossing = (_side(a[i], b[i], a[j]) * _side(a[i], b[i], b[j]) < 0) & (_side(a[j], b[j], a[i]) * _side(a[j], b[j], b[i]) < 0)
    return int(crossing.sum())


def generate_teeth(design: GearPairDesign, module: float, alpha: float, source: str) -> PairTeeth:
    n1, n2 = design.orders
    teeth = [design.perimeters[0] / (np.pi * module), design.perimeters[1] / (np.pi * module)]
    if max(abs(z - round(z)) for z in teeth) > 1e-6:
        raise InfeasibleError(f"{source}: tooth profiles need whole tooth counts, got {teeth[0]:.6f} and {teeth[1]:.6f} "
                              f"for module {module:g}: give pair.teeth to scale the curves to pi m Z")
    limit = ADDENDUM * module / np.sin(alpha) ** 2
    for gear, name in ((0, "driver"), (1, "driven")):
        concave = design.convexity[gear] <= 0
        if concave.any():
            k = int(np.flatnonzero(concave)[0])
            raise InfeasibleError(
                f"{source}: the {name} pitch curve is concave at phi1 = {np.degrees(design.phi1[k]):.2f} deg: a rack "
                f"cutter cannot generate it (a shaper cutter would be needed, not implemented)")
        rho = design.curvature_radius[gear]
        if rho.min() < limit:
            k = int(np.argmin(rho))
            raise InfeasibleError(
                f"{source}: module {module:g} undercuts the {name}: curvature radius {rho[k]:.3f} mm at phi1 = "
                f"{np.degrees(design.phi1[k]):.2f} deg is below m / sin^2(alpha) = {limit:.3f} mm; "
                f"use a module up to {rho.min() * np.sin(alpha) ** 2 / ADDENDUM:.4f} mm or a larger curve")
    tables = (driver_table(design), driven_table(design))
    counts = [int(round(z)) for z in teeth]
    pitch = design.perimeters[0] / counts[0]
    profiles = tuple(rack_profile(table, count, module, alpha, design.curvature_radius[g], design.convexity[g],
                                  first_tooth_at=0.0 if g == 0 else pitch / 2)
                     for g, (table, count) in enumerate(zip(tables, counts)))
    ratio = local_contact_ratio(*design.curvature_radius, module, alpha)
    return PairTeeth(profiles, (float(ratio.min()), float(ratio.max())),
                     tuple(self_intersections(p.outline) for p in profiles))

"""Tooth profiles of both gears of a designed pair, with undercut, concavity and contact-ratio checks."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.errors import InfeasibleError
from transplanter.gears.pair import GearPairDesign
from transplanter.gears.rack_teeth import ADDENDUM, pitch_table, rack_profile
from transplanter.gears.swept_teeth import mate_profile, shaper_profile
from transplanter.geometry.self_crossings import crossing_segments


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
    outlines: tuple[np.ndarray, np.ndarray]       # closed outlines in each gear's frame (mm)
    counts: tuple[int, int]
    cutter: str
    contact_ratio: tuple[float, float] | None     # min, max of the local estimate where both curves are convex
    self_intersections: tuple[int, int]


def local_contact_ratio(rho1, rho2, module: float, alpha: float) -> np.ndarray:
    """Contact ratio of the spur pair that osculates the pitch curves at the contact point (convex parts)."""
    h = ADDENDUM * module

    def approach(rho):
        return np.sqrt((rho + h) ** 2 - (rho * np.cos(alpha)) ** 2) - rho * np.sin(alpha)

    return (approach(rho1) + approach(rho2)) / (np.pi * module * np.cos(alpha))


def self_intersections(outline: np.ndarray) -> int:
    """Proper crossings between segments of a closed outline (points in mm, the last joined to the first);
    touches, shared ends and collinear overlaps are not crossings (``geometry.self_crossings``)."""
    return len(crossing_segments(outline)[0])


def _refuse_what_the_cutter_cannot_cut(design: GearPairDesign, module: float, alpha: float, cutter: str,
                                       cutter_teeth: int, source: str):
    limit = ADDENDUM * module / np.sin(alpha) ** 2
    cutter_radius = module * cutter_teeth / 2
    for gear, name in ((0, "driver"), (1, "driven")):
        concave = design.convexity[gear] <= 0
        if concave.any() and cutter == "rack":
            k = int(np.flatnonzero(concave)[0])
            raise InfeasibleError(
                f"{source}: the {name} pitch curve is concave at phi1 = {np.degrees(design.phi1[k]):.2f} deg: a rack "
                f"cutter cannot generate it; set pair.cutter = \"shaper\"")
        if concave.any() and gear == 0:     # with a shaper only the driver meets the cutter
            hollow = float(np.abs(design.curvature_radius[gear][concave]).min())
            if cutter_radius >= hollow:
                raise InfeasibleError(
                    f"{source}: pair.shaper_teeth = {cutter_teeth}: the cutter's pitch radius {cutter_radius:.3f} mm "
                    f"does not fit the {name}'s concave curvature radius {hollow:.3f} mm; use at most "
                    f"{int(np.ceil(2 * hollow / module)) - 1} cutter teeth")
        # the rack criterion, also a guide for the shaper
        rho = np.where(concave, np.inf, design.curvature_radius[gear])
        if rho.min() < limit:
            k = int(np.argmin(rho))
            raise InfeasibleError(
                f"{source}: module {module:g} undercuts the {name}: curvature radius {rho[k]:.3f} mm at phi1 = "
                f"{np.degrees(design.phi1[k]):.2f} deg is below m / sin^2(alpha) = {limit:.3f} mm; "
                f"use a module up to {rho.min() * np.sin(alpha) ** 2 / ADDENDUM:.4f} mm or a larger curve; where "
                f"pair.teeth sets the size, the curve shrinks with the module: use more teeth (about "
                f"{limit / rho.min():.3g} times as many) or a larger pressure angle")


def generate_teeth(design: GearPairDesign, module: float, alpha: float, source: str,
                   cutter: str = "rack", cutter_teeth: int = 16) -> PairTeeth:
    """Both tooth outlines; the driver's tooth 0 and the driven gear's tooth space 0 meet at phi1 = 0."""
    teeth = [design.perimeters[0] / (np.pi * module), design.perimeters[1] / (np.pi * module)]
    if max(abs(z - round(z)) for z in teeth) > 1e-6:
        raise InfeasibleError(f"{source}: tooth profiles need whole tooth counts, "
                              f"got {teeth[0]:.6f} and {teeth[1]:.6f} for module {module:g}: "
                              "give pair.teeth to scale the curves to pi m Z")
    _refuse_what_the_cutter_cannot_cut(design, module, alpha, cutter, cutter_teeth, source)
    counts = (int(round(teeth[0])), int(round(teeth[1])))
    pitch = design.perimeters[0] / counts[0]
    tables = (driver_table(design), driven_table(design))
    if cutter == "rack":    # one rack cuts both: its two sides are complementary, so the pair is conjugate
        driver, driven = (rack_profile(table, count, module, alpha, first)
                          for table, count, first in zip(tables, counts, (0.0, pitch / 2), strict=True))
    else:                   # the shaper cuts the driver; the driver's teeth cut the driven gear (conjugate)
        driver = shaper_profile(tables[0], module, alpha, cutter_teeth)
        driven = mate_profile(design, driver, tables[1], module)
    both = (design.convexity[0] > 0) & (design.convexity[1] > 0)
    ratio = local_contact_ratio(design.curvature_radius[0][both], design.curvature_radius[1][both], module, alpha)
    return PairTeeth((driver, driven), counts, cutter,
                     (float(ratio.min()), float(ratio.max())) if ratio.size else None,
                     (self_intersections(driver), self_intersections(driven)))

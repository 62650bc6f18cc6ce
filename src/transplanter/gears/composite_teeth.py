"""Composite teeth of a pitch curve with corners (the cusp-pitch-curve paper, sections 2-3): variable involute
on the smooth stretches, incomplete cycloids on the tooth that stands on each corner, the driven gear by envelope.

Layout. No cutter can roll round a corner, so a tooth straddles each (convex) corner J: its
flanks cross the pitch curve at A = J - u and D = J + w, and between corners the regular teeth and
spaces keep the pitch p = pi m. Going round from corner j to corner j + 1 (arc L_j) there is a
space, k_j regular teeth and spaces, so w_j + u_(j+1) = L_j - p/2 - k_j p; k_j is the count that
leaves about one pitch and the remainder is split evenly, so the corner tooth is about a pitch
thick (the cusp-pitch-curve paper, section 2.3, asks h_vc in [0.8, 1.2] of the involute pitch h; the
package refuses a tooth count that leaves a corner tooth outside, naming counts that fit).

Flanks. Each smooth stretch is cut by the library's shaper (``swept_teeth.shaper_profile``: a
pinion cutter rolling on the pitch curve, the variable involute of the cusp-pitch-curve paper, eq 1-6) with
its teeth on that stretch's grid; the corner tooth keeps the shaper's flanks below the pitch curve and
rises from A and D on incomplete cycloids (``cycloid_teeth``) to the tip, one module above the
pitch curve. The driven gear is cut by the driver's outline in the pair's motion
(``swept_teeth.mate_profile``), so the pair is conjugate wherever the driver is.
"""
from __future__ import annotations

import dataclasses
import re
from dataclasses import dataclass

import numpy as np
import shapely
import shapely.affinity

from transplanter import progress
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.gears.composite_curve import CompositeCurve, cusps
from transplanter.gears.cycloid_teeth import (
    STRAIGHT_POINTS,
    CycloidArch,
    arch,
    arch_pressure_range,
    corner_heights,
    polyline_min_curvature_radius,
)
from transplanter.gears.mesh_check import MeshCheck, check_mesh
from transplanter.gears.pair import GearPairDesign, arc_to_angle, driven_angle
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.gears.swept_teeth import BIN_MODULES, shaper_profile
from transplanter.gears.teeth import driver_table, self_intersections
from transplanter.gears.tooth_contact import ContactRatio, measure_contact_ratio
from transplanter.gears.variable_involute import InvoluteDeviation, involute_deviation

#: The driven gear is carved by the driver's teeth within this many pitches of the contact, at positions this
#: many modules of pitch arc apart (at 0.05 the slivers left between positions read as one-position spikes of
#: transmission error up to 0.014 mm), the teeth's outline simplified within this many modules.
CARVE_REACH_PITCHES, CARVE_STEP_MODULES, CARVE_SIMPLIFY_MODULES = 1.5, 0.025, 1e-4
#: Mesh-check positions per tooth. Past a corner the transmission error can rise and fall within 2-4 deg of driver
#: turn: at the default 8 per tooth (1.5 deg apart on the example) the check read the example's peak with a 30-deg
#: corner pressure angle as 0.0046 mm, at 16 and 32 as 0.0088 mm.
MESH_SAMPLES_PER_TOOTH = 32
#: Corner pressure angles (deg) tried in turn when the problem gives none (docs/gear.md, the limits measured on the
#: ellipse-and-chord family): at 23-deg corners 22 passes for 28-32 teeth, where 30 fails past the corner for 31 and
#: 32; at 31-deg corners 22 fails just before the corner and 26 passes; at 39-deg corners with 28 and 29 teeth only 38
#: passes. An angle whose arch would stand above the tip is refused before any cutting, so trying it costs nothing.
CORNER_PRESSURE_TRIALS_DEG = (22.0, 26.0, 30.0, 34.0, 38.0)
#: The corner tooth's thickness at the pitch curve, as a fraction of the pitch (the cusp-pitch-curve paper,
#: section 2.3).
THICKNESS_BAND = (0.8, 1.2)


@dataclass(frozen=True)
class CornerTooth:
    """The tooth on one corner: pitch arc (mm) of the corner and of its flanks' pitch points, its arches."""

    corner_arc: float
    start_arc: float            # A
    end_arc: float              # D
    pitch: float
    arches: tuple[CycloidArch, CycloidArch]
    joint_kinks_deg: tuple[float, float]    # turn of the outline where each flank leaves the involute below it
    joint_gaps_mm: tuple[float, float]
    # each side's straight flank and arch from its pitch point, as cut at the tip
    flanks: tuple[np.ndarray, np.ndarray]
    pressure_angles_deg: tuple[tuple[float, float], tuple[float, float]]   # each arch's, as cut at the tip
    min_curvature_radius_mm: tuple[float, float]                           # each arch's, as cut at the tip

    @property
    def thickness_ratio(self) -> float:
        return (self.end_arc - self.start_arc) / self.pitch


@dataclass(frozen=True)
class Layout:
    """Corner arcs (mm), their zones u (before) and w (after), regular teeth k between corners."""

    corners: np.ndarray
    before: np.ndarray
    after: np.ndarray
    between: np.ndarray
    pitch: float

    @property
    def thickness_ratios(self) -> np.ndarray:
        return (self.before + self.after) / self.pitch

    def space_centers(self, perimeter: float) -> np.ndarray:
        """Pitch arcs (mm, ascending in [0, perimeter)) of the driver's tooth-space centres."""
        ends = self.corners + self.after
        centers = [end + self.pitch / 4 + i * self.pitch
                   for end, k in zip(ends, self.between, strict=True) for i in range(k + 1)]
        return np.sort(np.mod(centers, perimeter))


def layout(corners: np.ndarray, perimeter: float, pitch: float) -> Layout:
    """Split the pitch curve among corner teeth and regular teeth (module docstring)."""
    gaps = np.diff(np.r_[corners, corners[0] + perimeter])
    between = np.maximum(0, np.round((gaps - 1.5 * pitch) / pitch)).astype(int)
    rest = gaps - pitch / 2 - between * pitch
    return Layout(corners, np.roll(rest, 1) / 2, rest / 2, between, pitch)


def _check_layout(plan: Layout, teeth: int, segment_arcs: list[tuple[float, float]], source: str):
    low, high = THICKNESS_BAND
    ratios = plan.thickness_ratios
    if ((ratios < low) | (ratios > high)).any():
        k = int(np.argmax(np.abs(ratios - 1)))
        fits = [z for z in range(max(3, teeth - 12), teeth + 13) if _fits(plan, teeth, z)]
        raise InfeasibleError(
            f"{source}: pair.teeth = {teeth}: the tooth on the corner at pitch arc {plan.corners[k]:.3f} mm would be "
            f"{ratios[k]:.3f} pitches thick, outside [{low}, {high}] (the cusp-pitch-curve paper, section 2.3); tooth "
            f"counts that keep every corner tooth in the band: {', '.join(map(str, fits)) or 'none within 12 of it'} "
            f"(whether they mesh is checked when they are cut)")
    for k, (corner, (before, after)) in enumerate(zip(plan.corners, segment_arcs, strict=True)):
        for zone, room, name in ((plan.before[k], before, "before"), (plan.after[k], after, "after")):
            if zone >= room:
                raise InfeasibleError(
                    f"{source}: pair.teeth = {teeth}: the cusp zone of {zone:.3f} mm {name} the corner at pitch arc "
                    f"{corner:.3f} mm is wider than the segment there ({room:.3f} mm); "
                    "use more teeth or a longer segment")


def _fits(plan: Layout, teeth: int, candidate: int) -> bool:
    """Whether ``candidate`` teeth (the curve scaled to pi m candidate) keep every corner tooth in the band."""
    scale = candidate / teeth
    perimeter = teeth * plan.pitch * scale
    ratios = layout(plan.corners * scale, perimeter, plan.pitch).thickness_ratios
    return bool(((ratios >= THICKNESS_BAND[0]) & (ratios <= THICKNESS_BAND[1])).all())


@dataclass(frozen=True)
class CornerPressureTrial:
    """One corner pressure angle tried (deg): refused before cutting (``refused`` says why), or cut and judged
    (its failures and transmission error, mm)."""

    degrees: float
    refused: str | None = None
    failures: tuple[str, ...] = ()
    transmission_error_mm: float | None = None

    @property
    def passed(self) -> bool:
        return self.refused is None and not self.failures


@dataclass(frozen=True)
class CompositeTeeth:
    """Both outlines (mm, each gear's frame) and what was built and measured on the way."""

    outlines: tuple[np.ndarray, np.ndarray]
    counts: tuple[int, int]
    plan: Layout
    corner_teeth: tuple[CornerTooth, ...]
    self_intersections: tuple[int, int]
    mesh: MeshCheck
    contact: ContactRatio
    involute: InvoluteDeviation     # the shaper-cut stretches against the closed-form variable involute
    corner_pressure_deg: float      # theta_J / 2 of the arches
    trials: tuple[CornerPressureTrial, ...] = ()   # the corner pressure angles tried when none was given
    cutter: str = "composite"

    @property
    def contact_ratio(self) -> tuple[float, float]:
        return float(np.nanmin(self.contact.ratios)), float(np.nanmax(self.contact.ratios))

    @property
    def failures(self) -> list[str]:
        """Contact lost on a flank side somewhere in the cycle, self-intersections, and the mesh check's failures."""
        found = []
        where = self.contact.where()
        if self.contact.minimum < 1:
            found.append(f"contact ratio {self.contact.minimum:.3f} below 1 on the {where.flank} flank of the "
                         f"tooth at {where.phi_deg:.2f} deg")
        for flank, angles in zip(("low-arc", "high-arc"), self.contact.uncovered_deg, strict=True):
            if angles.size:
                found.append(f"no {flank} flank touches (contact ratio below 1) at {angles.size} of the sampled "
                             f"positions, first at driver angle {angles[0]:.2f} deg")
        if any(self.self_intersections):
            found.append(f"self-intersecting tooth outlines: {list(self.self_intersections)} crossings")
        return found + self.mesh.failures

    @property
    def passed(self) -> bool:
        return not self.failures


def _pitch_heights(points: np.ndarray, pitch_curve: shapely.Polygon) -> np.ndarray:
    """Distance (mm) of points outside the pitch curve from it (0 inside)."""
    return np.asarray(shapely.distance(pitch_curve, shapely.points(points)))


def _to_tip(arch_points: np.ndarray, heights: np.ndarray, tip: float) -> np.ndarray:
    """The arch up to where it reaches the tip height (the crossing interpolated)."""
    above = np.flatnonzero(heights > tip)
    if not above.size:
        return arch_points
    k = int(above[0])
    w = (tip - heights[k - 1]) / (heights[k] - heights[k - 1])
    return np.r_[arch_points[:k], (arch_points[k - 1] + w * (arch_points[k] - arch_points[k - 1]))[None]]


def _tip(first: np.ndarray, last: np.ndarray, pitch_curve: shapely.Polygon, tip: float, count: int = 40) -> np.ndarray:
    """The tooth's top between its two arches' ends, on the addendum band (the pitch curve grown by ``tip``):
    an arc about the corner where the corner is nearest, as a rack-cut tooth's tip would be."""
    chord = first + np.linspace(0.0, 1.0, count + 2)[1:-1, None] * (last - first)
    boundary = pitch_curve.exterior
    nearest = shapely.get_coordinates(boundary.interpolate(boundary.project(shapely.points(chord))))
    away = chord - nearest
    return nearest + tip * away / np.linalg.norm(away, axis=1, keepdims=True)


def _turn_deg(first: np.ndarray, second: np.ndarray) -> float:
    cross = first[0] * second[1] - first[1] * second[0]
    return float(np.degrees(np.arctan2(cross, np.dot(first, second))))


def _largest_corner_pressure(zone: float, alpha: float, tip: float) -> str:
    """'use at most X deg': the largest corner pressure angle at which an arch over ``zone`` reaches the corner below
    the tip (from alpha up to the first angle that fails)."""
    angles = np.linspace(alpha, np.pi / 2, 2001)[1:]
    low = corner_heights(zone, alpha, 2 * angles) < tip
    fits = angles[:int(np.argmin(low))] if not low.all() else angles
    if not fits.size:
        return "no angle fits: use more teeth"
    return f"use at most {np.floor(np.degrees(fits.max()) * 10) / 10:.1f} deg"


def _check_arch_height(zone: float, alpha: float, corner_pressure: float, tip: float, corner: float, source: str):
    """Refuse a corner pressure angle at which an arch over ``zone`` reaches the tip before its circle reaches the
    corner (it could not drive past the corner), naming the largest angle that passes."""
    height = float(corner_heights(zone, alpha, 2 * corner_pressure)[0])
    if height < tip:
        return
    raise InfeasibleError(
        f"{source}: pair.corner_pressure_angle_deg = {np.degrees(corner_pressure):g}: the cycloid arch of the corner "
        f"tooth at pitch arc {corner:.3f} mm would stand {height:.3f} mm high over the corner, above the tip "
        f"({tip:.3f} mm), and stop short of it; {_largest_corner_pressure(zone, alpha, tip)}")


def _check_arches_apart(rising: list[np.ndarray], radii: tuple[float, float], zone: float, alpha: float,
                        corner_pressure: float, tip: float, corner: float, source: str):
    """Refuse a corner tooth whose two cycloid flanks (each from its pitch point to the tip) cross: rolling circles
    too large for the tooth, which a larger corner pressure angle makes smaller."""
    if not shapely.LineString(rising[0]).intersects(shapely.LineString(rising[1])):
        return
    raise InfeasibleError(
        f"{source}: pair.corner_pressure_angle_deg = {np.degrees(corner_pressure):g}: the two cycloid flanks of the "
        f"corner tooth at pitch arc {corner:.3f} mm cross below its tip (rolling radii {radii[0]:.3f} and "
        f"{radii[1]:.3f} mm); a larger angle rolls smaller circles: {_largest_corner_pressure(zone, alpha, tip)}, "
        f"or use more teeth")


def generate_composite_teeth(design: GearPairDesign, module: float, alpha: float, teeth: int, cutter_teeth: int,
                             source: str, corner_pressure: float | None = None) -> CompositeTeeth:
    """Driver outline of shaper-cut stretches and corner teeth, the driven outline by envelope (module docstring).

    ``corner_pressure`` (rad) sets theta_J / 2 of every corner's arches; None tries ``CORNER_PRESSURE_TRIALS_DEG``
    above ``alpha`` in turn (smallest first: the contact passes the corner most squarely) and keeps the first pair
    that passes every check, or, when none does, the one with the smallest transmission error.

    Raises
    ------
    InfeasibleError
        When a corner is concave, a corner tooth leaves the thickness band, a cusp zone is wider than its segment,
        or, at the given corner pressure angle (at every one tried), an arch stands above the tip over its corner or
        a corner tooth's two cycloid flanks cross.
    """
    curve = design.driver
    if not isinstance(curve, CompositeCurve):
        raise ProblemError(f"{source}: driver.family = {curve.family!r}: expected \"composite\" (composite teeth "
                           "stand on the corners of a composite pitch curve)")
    perimeter, pitch = design.perimeters[0], np.pi * module
    corners = sorted(cusps(curve), key=lambda c: c["phi_deg"])
    concave = [c for c in corners if c["turn_deg"] < 0]
    if concave:
        raise InfeasibleError(f"{source}: driver.segments: the corner at {concave[0]['phi_deg']:.3f} deg turns "
                              f"{concave[0]['turn_deg']:.3f} deg (concave): "
                              "composite teeth stand on convex corners only: make the segments meet there at a "
                              "convex corner or without a corner")
    starts = [float(np.mod(s.start, 2 * np.pi)) for s in curve.segments]
    joint_index = [int(np.argmin(np.abs(np.radians(c["phi_deg"]) - np.array(starts)))) for c in corners]
    edge_arc = {float(phi): float(arc) for phi, arc in zip(design.phi1, design.arc, strict=True)}
    segment_start = np.array([edge_arc[min(edge_arc, key=lambda e: abs(e - start))] for start in starts])
    segment_length = np.mod(np.roll(segment_start, -1) - segment_start, perimeter)
    segment_length[segment_length == 0] = perimeter
    corner_arc = np.array([segment_start[k] for k in joint_index])
    plan = layout(corner_arc, perimeter, pitch)
    _check_layout(plan, teeth, [(segment_length[k - 1], segment_length[k]) for k in joint_index], source)

    def arc_to_phi(s):
        return arc_to_angle(design, s)

    table = driver_table(design)
    count = int(np.ceil(perimeter / (BIN_MODULES * module)))
    bins = (np.arange(count) + 0.5) * perimeter / count
    pitch_curve = shapely.Polygon(design.points[0])
    tip = ADDENDUM * module
    stretches = []
    for j in range(len(corners)):
        end = corner_arc[j] + plan.after[j]
        next_start = corner_arc[(j + 1) % len(corners)] - plan.before[(j + 1) % len(corners)]
        run = np.mod(bins - end, perimeter)
        keep = np.flatnonzero(run <= np.mod(next_start - end, perimeter))
        with np.errstate(invalid="ignore"):
            stretch = shaper_profile(table, module, alpha, cutter_teeth, first_tooth_at=end - pitch / 4)[keep]
        if not np.isfinite(stretch).all():
            raise InfeasibleError(
                f"{source}: pair.teeth = {teeth}: the shaper path (swept_teeth) returned non-finite tooth heights "
                f"on the stretch after the corner at pitch arc {corner_arc[j]:.3f} mm; try another tooth count")
        stretches.append(stretch[np.argsort(run[keep])])

    def pair_at(corner_pressure: float) -> CompositeTeeth:
        pieces, corner_parts = [], []
        for j, k in enumerate(joint_index):
            start, end = corner_arc[j] - plan.before[j], corner_arc[j] + plan.after[j]
            zone = max(plan.before[j], plan.after[j])
            _check_arch_height(zone, alpha, corner_pressure, tip, corner_arc[j], source)
            left = arch(curve, arc_to_phi, corner_arc[j], plan.before[j], (k - 1, k), +1, alpha, 2 * corner_pressure)
            right = arch(curve, arc_to_phi, corner_arc[j], plan.after[j], (k, k - 1), -1, alpha, 2 * corner_pressure)
            rising = [_to_tip(a.points, _pitch_heights(a.points, pitch_curve), tip) for a in (left, right)]
            _check_arches_apart(rising, (left.radius, right.radius), zone, alpha, corner_pressure, tip, corner_arc[j],
                                source)
            pieces += [np.r_[rising[0], _tip(rising[0][-1], rising[1][-1], pitch_curve, tip), rising[1][::-1]],
                       stretches[j]]
            corner_parts.append((j, start, end, (left, right), rising))
        driver = np.concatenate(pieces)
        _check_outline_simple(driver, corners, corner_pressure, source)
        corner_teeth = tuple(_corner_tooth(driver, corner_arc[j], start, end, pitch, arches, rising)
                             for j, start, end, arches, rising in corner_parts)
        driven = carved_mate(design, driver, module)
        built = int(plan.between.sum()) + len(corners)
        outlines = (driver, driven)
        return CompositeTeeth(outlines, (built, int(round(built * design.orders[1] / design.orders[0]))), plan,
                              corner_teeth, (self_intersections(driver), self_intersections(driven)),
                              check_mesh(design, outlines, module, MESH_SAMPLES_PER_TOOTH),
                              measure_contact_ratio(design, outlines, module, plan.space_centers(perimeter)),
                              _against_closed_form(table, driver, plan, perimeter, module, alpha, cutter_teeth),
                              float(np.degrees(corner_pressure)))

    if corner_pressure is not None:
        return pair_at(corner_pressure)
    # the arch starts leaning alpha, so it can only pass the corner at more; alpha stops at 35 deg (GearProblem)
    return _first_that_passes(pair_at, [d for d in CORNER_PRESSURE_TRIALS_DEG if np.radians(d) > alpha])


def _check_outline_simple(driver: np.ndarray, corners: list[dict], corner_pressure: float, source: str):
    """Refuse a driver outline that crosses itself (the driven gear cannot be carved from it): corner teeth on
    corners too sharp for the arches, whose tooth runs into its neighbours'."""
    reason = shapely.is_valid_reason(shapely.Polygon(driver))
    found = re.search(r"\[(\S+) (\S+)\]", reason)
    if reason == "Valid Geometry" or found is None:
        return
    x, y = float(found[1]), float(found[2])
    angle = np.degrees(np.arctan2(y, x))
    near = min(corners, key=lambda c: abs(np.mod(angle - c["phi_deg"] + 180, 360) - 180))
    raise InfeasibleError(
        f"{source}: pair.corner_pressure_angle_deg = {np.degrees(corner_pressure):g}: the driver's tooth outline "
        f"crosses itself at ({x:.3f}, {y:.3f}) mm, by the corner at {near['phi_deg']:.3f} deg, which turns the "
        f"tangent by {near['turn_deg']:.1f} deg (driver.segments): the composite teeth carry corners of up to about "
        f"31 deg (docs/gear.md); turn the corners less")


def _first_that_passes(pair_at, angles: list[float]) -> CompositeTeeth:
    """``pair_at(corner pressure angle)`` over ``angles`` (deg): the first pair that passes, else the one with the
    smallest transmission error, with every trial's outcome; the first refusal when every angle is refused."""
    trials, built = [], []
    refusals: list[InfeasibleError] = []
    for degrees in angles:
        try:
            with progress.step(f"corner pressure angle {degrees:g} deg"):
                teeth = pair_at(float(np.radians(degrees)))
        except InfeasibleError as error:
            refusals.append(error)
            trials.append(CornerPressureTrial(degrees, refused=str(error).split(": ", 1)[-1]))
            continue
        trials.append(CornerPressureTrial(degrees, failures=tuple(teeth.failures),
                                          transmission_error_mm=teeth.mesh.max_transmission_error_mm))
        built.append(teeth)
        if teeth.passed:
            break
    if not built:
        raise refusals[0]
    best = built[-1] if built[-1].passed else min(built, key=lambda t: t.mesh.max_transmission_error_mm)
    return dataclasses.replace(best, trials=tuple(trials))


def _against_closed_form(table, driver: np.ndarray, plan: Layout, perimeter: float, module: float, alpha: float,
                         cutter_teeth: int) -> InvoluteDeviation:
    """The shaper-cut flanks (every space's two; at a corner tooth's A and D only below the pitch curve, where the
    shaper cut them) against the closed-form variable involute."""
    pitch = np.pi * module
    centers = plan.space_centers(perimeter)
    flanks = np.mod(np.r_[centers - pitch / 4, centers + pitch / 4], perimeter)
    sides = np.r_[-np.ones(len(centers)), np.ones(len(centers))]
    corner_flanks = np.mod(np.r_[plan.corners - plan.before, plan.corners + plan.after], perimeter)
    apart = np.abs(np.mod(flanks[:, None] - corner_flanks[None] + perimeter / 2, perimeter) - perimeter / 2)
    return involute_deviation(table, driver, flanks, sides, apart.min(axis=1) > 1e-6 * pitch, plan.corners, module,
                              alpha, cutter_teeth)


def carved_mate(design: GearPairDesign, driver: np.ndarray, module: float) -> np.ndarray:
    """The driven outline as its blank (the pitch curve grown by the addendum) less the driver's teeth placed
    in the driven gear's frame at positions CARVE_STEP_MODULES of pitch arc apart through one driven turn.

    The driver's outline, simplified within CARVE_SIMPLIFY_MODULES, is cut to a disc of CARVE_REACH_PITCHES
    about the contact at each position. ``swept_teeth.mate_profile`` bins the cut along the driven pitch
    curve's normals instead; at the concave corner that every driver corner makes on the driven curve
    (derivations/cusp.py) those normals cross above the pitch curve and fan apart below it, so bins there
    collect cuts from the wrong side or none (overlaps of 0.03 mm at module 2 on the example). Polygon
    differences have no such frame.
    """
    perimeter = design.perimeters[0]
    n1, n2 = design.orders
    arcs = np.arange(0.0, perimeter * n2 / n1, CARVE_STEP_MODULES * module)
    phi1 = np.interp(np.mod(arcs, perimeter), design.arc, design.phi1) + 2 * np.pi * np.floor(arcs / perimeter)
    phi2 = driven_angle(design, phi1)
    contact = np.interp(np.mod(arcs, perimeter), design.arc, np.arange(len(design.arc)))
    body = shapely.simplify(shapely.Polygon(driver), CARVE_SIMPLIFY_MODULES * module)
    shapely.prepare(body)
    centers = design.points[0][np.round(contact).astype(int)]
    discs = shapely.buffer(shapely.points(centers), CARVE_REACH_PITCHES * np.pi * module, quad_segs=8)
    teeth = shapely.intersection(body, discs)
    placed = []
    for tooth, a, b in zip(teeth, phi1, phi2, strict=True):
        points = shapely.get_coordinates(tooth)
        c1, s1 = np.cos(-a), np.sin(-a)
        world = points @ np.array([[c1, s1], [-s1, c1]]) - [design.center_distance, 0.0]
        c2, s2 = np.cos(-b), np.sin(-b)
        placed.append(_with_coordinates(tooth, world @ np.array([[c2, s2], [-s2, c2]])))
    blank = shapely.Polygon(design.points[1][:-1]).buffer(ADDENDUM * module, quad_segs=64)
    driven = blank.difference(shapely.union_all(placed))
    largest = max(shapely.get_parts(driven), key=lambda g: g.area)     # the carved blank may fall apart
    return shapely.get_coordinates(shapely.get_exterior_ring(largest))[:-1]


def _with_coordinates(geometry, coordinates: np.ndarray):
    """``geometry`` with its coordinates replaced by ``coordinates`` (same count, same order)."""
    return shapely.transform(geometry, lambda _: coordinates)


def _corner_tooth(outline, corner, start, end, pitch, arches, rising) -> CornerTooth:
    """The joints of a corner tooth's arches with the involute below them: the outline's turn and gap there."""
    n = len(outline)

    def joint(points: np.ndarray, after: bool) -> tuple[float, float]:
        at = int(np.argmin(np.linalg.norm(outline - points[0], axis=1)))      # the arch's pitch point in the outline
        if after:       # outline runs down the arch to D, then down the involute
            arch_way, involute_way = points[0] - points[1], outline[(at + 4) % n] - outline[(at + 1) % n]
            return abs(_turn_deg(arch_way, involute_way)), float(np.linalg.norm(outline[(at + 1) % n] - points[0]))
        # outline runs up the involute to A, then up the arch
        involute_way, arch_way = outline[at - 1] - outline[at - 4], points[1] - points[0]
        return abs(_turn_deg(involute_way, arch_way)), float(np.linalg.norm(outline[at - 1] - points[0]))

    (kink_a, gap_a), (kink_d, gap_d) = joint(rising[0], False), joint(rising[1], True)
    left, right = rising
    return CornerTooth(float(corner), float(start), float(end), pitch, arches, (kink_a, kink_d), (gap_a, gap_d),
                       (left, right),
                       (arch_pressure_range(arches[0], len(left) - STRAIGHT_POINTS),
                        arch_pressure_range(arches[1], len(right) - STRAIGHT_POINTS)),
                       (polyline_min_curvature_radius(left[STRAIGHT_POINTS:]),
                        polyline_min_curvature_radius(right[STRAIGHT_POINTS:])))

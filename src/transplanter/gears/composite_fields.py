"""The ``[[driver.segments]]`` tables of a composite pitch curve (mm, degrees) -> ``CompositeCurve``.

    [[driver.segments]]
    kind = "ellipse"              # line, arc, or a family: ellipse, higher_order_ellipse,
                                  # denatured_ellipse, limacon, denatured_limacon, spline
    phi_deg = [-150.0, 150.0]     # the segment's angle range, counterclockwise; the next starts where it ends
    rotation_deg = 0.0            # a family's curve turned counterclockwise (default 0)
    semi_major_axis = 30.0        # ... and the family's own fields
    [[driver.segments]]
    kind = "line"
    phi_deg = [150.0, 210.0]
    distance = 10.0               # optional: the line x . e(normal) = distance; without distance and
    normal_deg = 180.0            # normal_deg, the chord between the neighbouring segments' ends
    [[driver.segments]]
    kind = "arc"
    center = [0.0, 0.0]           # mm
    radius = 20.0                 # mm
"""
from __future__ import annotations

import numpy as np

from transplanter.gears.composite_curve import Segment, arc, chord, composite, line, rotated
from transplanter.toml_fields import FieldReader, is_sequence

#: Most segments of a composite curve: its pitch curves' work grows with their number (measured on a circle cut
#: into arcs: 100 segments 7 s, 1000 segments 66 s).
LARGEST_SEGMENT_COUNT = 100
SEGMENT_FAMILIES = ("ellipse", "higher_order_ellipse", "denatured_ellipse", "limacon", "denatured_limacon", "spline")
_KIND_KEYS = {"line": {"distance", "normal_deg"}, "arc": {"center", "radius"}}
_COMMON = {"kind", "phi_deg", "rotation_deg"}


def _range(read: FieldReader, table: dict, where: str) -> tuple[float, float]:
    values = table.get("phi_deg")
    if not is_sequence(values) or len(values) != 2:
        read.fail(f"{where}.phi_deg", values, "[start, end] in degrees, counterclockwise")
    start, end = read.numbers(table, "phi_deg", where, minimum_count=2)
    if not start < end <= start + 360:
        read.fail(f"{where}.phi_deg", [float(start), float(end)], "start < end <= start + 360 (degrees)")
    return float(np.radians(start)), float(np.radians(end))


def read_composite(read: FieldReader, table: dict, where: str, read_family, family_keys: dict[str, set],
                   largest_samples: int):
    """Segments in order round the turn; ``read_family(read, table, where, families)`` reads a family's curve,
    whose own fields are ``family_keys[family]``; the spline segments hold at most ``largest_samples`` samples
    together (as many as one spline gear)."""
    rows = table.get("segments")
    if not isinstance(rows, (list, tuple)) or len(rows) < 2 or not all(isinstance(r, dict) for r in rows):
        read.fail(f"{where}.segments", rows, "at least two [[driver.segments]] tables")
    if len(rows) > LARGEST_SEGMENT_COUNT:
        read.fail(f"{where}.segments", f"{len(rows)} segments", f"at most {LARGEST_SEGMENT_COUNT} segments")
    samples = sum(len(row["radius"]) for row in rows if row.get("kind") == "spline" and is_sequence(row.get("radius")))
    if samples > largest_samples:
        read.fail(f"{where}.segments", f"{samples} spline samples", f"at most {largest_samples} spline samples over "
                  "all segments together (each segment's spline costs as a gear of its samples)")
    pieces = []
    for k, row in enumerate(rows):
        at = f"{where}.segments[{k}]"
        kind = row.get("kind")
        if kind not in (*_KIND_KEYS, *SEGMENT_FAMILIES):
            read.fail(f"{at}.kind", kind, "one of line, arc, " + ", ".join(SEGMENT_FAMILIES))
        start, end = _range(read, row, at)
        if kind == "line":
            read.keys(row, _COMMON - {"rotation_deg"} | _KIND_KEYS["line"], at)
            if ("distance" in row) != ("normal_deg" in row):
                read.fail(f"{at}.distance", row.get("distance"), "both distance and normal_deg, or neither (a chord)")
            curve = None if "distance" not in row else line(read.number(row, "distance", at),
                                                             float(np.radians(read.number(row, "normal_deg", at))))
        elif kind == "arc":
            read.keys(row, _COMMON - {"rotation_deg"} | _KIND_KEYS["arc"], at)
            radius = read.number(row, "radius", at)
            if radius <= 0:
                read.fail(f"{at}.radius", radius, "a positive radius (mm)")
            center = read.point(row.get("center"), f"{at}.center")
            if np.hypot(*center) >= radius:
                read.fail(f"{at}.center", center.tolist(), f"a point inside the circle (nearer the gear centre than "
                                                           f"the radius {radius:g} mm), so every ray meets it once")
            curve = arc(tuple(center), radius)
        else:
            read.keys(row, _COMMON | family_keys[kind], at)
            family = {key: value for key, value in row.items() if key not in _COMMON}
            curve = read_family(read, {"family": kind, **family}, at, SEGMENT_FAMILIES)
            rotation = float(np.radians(read.number(row, "rotation_deg", at))) if "rotation_deg" in row else 0.0
            curve = rotated(curve, rotation) if rotation else curve
        pieces.append([kind, start, end, curve])
    ends = {}
    for k, (_, start, end, curve) in enumerate(pieces):
        if curve is None:   # a chord: from the previous segment's end to the next one's start
            before, after = pieces[k - 1], pieces[(k + 1) % len(pieces)]
            if before[3] is None or after[3] is None:
                read.fail(f"{where}.segments[{k}]", "line without distance", "a neighbour that is not a chord as well")
            ends[k] = [before[3].evaluate(np.array([start]))[0][0] * np.array([np.cos(start), np.sin(start)]),
                       after[3].evaluate(np.array([end]))[0][0] * np.array([np.cos(end), np.sin(end)])]
    for k, points in ends.items():
        pieces[k][3] = chord(*points)
    return composite([Segment(kind, start, end, curve, kind == "line") for kind, start, end, curve in pieces],
                     read.source, f"{where}.segments")

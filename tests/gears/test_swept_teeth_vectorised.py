"""The swept-teeth envelope, cut a chunk of positions at a time as arrays, against a plain reference that walks
the positions one by one over the whole outline; the pitch table's interpolation against the Hermite helper."""
import numpy as np
import pytest

from transplanter.gears import swept_teeth
from transplanter.gears.teeth import driven_table, driver_table
from transplanter.geometry.hermite import hermite

from .ellipse_pair import ALPHA, CUTTER_TEETH, GEARS, MODULE, driver_outline, ellipse_pair, swept_outline


def test_pitch_table_interpolates_as_the_hermite_of_its_samples():
    """Points are the cubic Hermite of the samples with the unit tangents as slopes, tangents the normalised
    linear blend of the sample tangents, normals those turned outward, on both gears of the pair (at and next to
    every sample too, where the interval is looked up)."""
    design = ellipse_pair()
    for table in (driver_table(design), driven_table(design)):
        knots = table.arc[:-1]
        s = np.r_[np.linspace(-table.perimeter, 2 * table.perimeter, 5001), knots, np.nextafter(knots, -1),
                  np.nextafter(knots, np.inf), table.perimeter]
        point, tangent, normal = table.at(s)
        arc = np.mod(s, table.perimeter)
        expected = hermite(table.arc, table.points, table.tangents[:-1], table.tangents[1:], arc)
        k = np.clip(np.searchsorted(table.arc, arc, side="right") - 1, 0, len(table.arc) - 2)
        t = ((arc - table.arc[k]) / np.diff(table.arc)[k])[:, None]
        blend = (1 - t) * table.tangents[k] + t * table.tangents[k + 1]
        blend /= np.linalg.norm(blend, axis=1, keepdims=True)
        assert np.abs(point - expected).max() < 1e-9
        assert np.abs(tangent - blend).max() < 1e-12
        assert np.abs(normal - table.orientation * np.c_[blend[:, 1], -blend[:, 0]]).max() < 1e-12


def _per_position_heights(table, tip_height, outline, place, positions):
    """Bin heights the swept ``outline`` leaves, one position at a time, every vertex taking part: at position k
    the segments are the outline's edges and each vertex's chord to position k + 1 (the last position: its
    edges only). A segment cuts where it crosses a bin edge if one end lies below the tip and both ends were
    projected; a vertex is projected when inside the grown tip or on a segment with an end there. The projection
    itself is the package's (``PitchTable.normal_coordinates``); what is checked is which segments cut which bins."""
    perimeter = table.perimeter
    count = int(np.ceil(perimeter / (swept_teeth.BIN_MODULES * MODULE)))
    width = perimeter / count
    height = np.full(count, tip_height)
    radial_arc = swept_teeth._radial_arc(table)
    tip = table.points + (tip_height + swept_teeth.MARGIN_MODULES * MODULE) * table.normals
    tip_angle = np.arctan2(tip[:, 1], tip[:, 0])
    order = np.argsort(tip_angle)
    n = len(outline)
    edges = np.c_[np.arange(n), (np.arange(n) + 1) % n]
    for k in range(positions):
        last = k == positions - 1
        points = place(outline, np.array([k] if last else [k, k + 1])).reshape(-1, 2)
        pairs = edges if last else np.r_[edges, np.c_[np.arange(n), np.arange(n) + n]]
        angle = np.arctan2(points[:, 1], points[:, 0])
        bound = np.interp(angle, tip_angle[order], np.sum(tip[order] ** 2, axis=1), period=2 * np.pi)
        inside = np.sum(points ** 2, axis=1) < bound
        projected = inside.copy()
        for end in (0, 1):
            projected[pairs[:, end][inside[pairs].any(axis=1)]] = True
        s, h = np.zeros(len(points)), np.full(len(points), np.inf)
        s[projected], h[projected] = table.normal_coordinates(points[projected],
                                                              radial_arc(swept_teeth._polar(points[projected])[0]),
                                                              swept_teeth.CONVERGED_MODULES * MODULE)
        below = h < tip_height
        for j in np.flatnonzero(below):
            bin_ = min(int(s[j] / width), count - 1)
            height[bin_] = min(height[bin_], h[j])
        cutting = pairs[below[pairs].any(axis=1) & projected[pairs].all(axis=1)]
        s_a, s_b, h_a, h_b = s[cutting[:, 0]], s[cutting[:, 1]], h[cutting[:, 0]], h[cutting[:, 1]]
        run = np.mod(s_b - s_a + perimeter / 2, perimeter) - perimeter / 2
        low_s, low_h, high_h = (np.where(run < 0, s_b, s_a), np.where(run < 0, h_b, h_a),
                                np.where(run < 0, h_a, h_b))
        first, last_edge = np.floor(low_s / width), np.floor((low_s + np.abs(run)) / width)
        for step in range(1, int((last_edge - first).max(initial=0)) + 1):
            on = last_edge - first >= step
            edge = (first[on] + step).astype(int)
            level = low_h[on] + (edge * width - low_s[on]) / np.abs(run[on]) * (high_h[on] - low_h[on])
            np.minimum.at(height, edge % count, level)
            np.minimum.at(height, (edge - 1) % count, level)
    return height


@pytest.mark.parametrize("gear", GEARS)
def test_envelope_matches_the_per_position_reference(gear, monkeypatch):
    """On a 20-tooth ellipse pair of module 2, the outline each profile returns lies on the reference's bin heights
    to 1e-9 mm."""
    design = ellipse_pair()
    tables = driver_table(design), driven_table(design)
    driver = swept_teeth.shaper_profile(tables[0], MODULE, ALPHA, CUTTER_TEETH)
    swept = []
    chunked = swept_teeth._positions

    def recording(points, facing, reach, place, **options):
        swept.append((points, place, len(facing)))
        return chunked(points, facing, reach, place, **options)

    monkeypatch.setattr(swept_teeth, "_positions", recording)
    if gear == GEARS[0]:
        table = tables[0]
        outline = swept_teeth.shaper_profile(table, MODULE, ALPHA, CUTTER_TEETH)
    else:
        table = tables[1]
        outline = swept_teeth.mate_profile(design, driver, table, MODULE)
    (points, place, positions), = swept
    height = _per_position_heights(table, swept_teeth.ADDENDUM * MODULE, points, place, positions)
    width = table.perimeter / len(height)
    foot, _, normal = table.at((np.arange(len(height)) + 0.5) * width)
    assert np.abs(outline - (foot + height[:, None] * normal)).max() < 1e-9
    assert height.min() < 0      # the teeth were cut, not the bare blank


class _AloneTwin:
    """A twin whose other process cut nothing: each half's own cut comes out."""

    def __init__(self, index: int):
        self.index = index

    def swap(self, value):
        return np.full_like(value, np.inf)


@pytest.mark.parametrize("gear", GEARS)
def test_halves_cut_by_twins_merge_to_the_whole_cut(gear):
    """Each twin cuts half the chunks of an envelope's positions; on each bin (along the same normal) the lower
    of the two halves' outlines is the outline one process cuts, to the last bit, and neither half is it alone."""
    design = ellipse_pair()
    driver = driver_outline(design)
    whole = swept_outline(gear, design, driver)
    halves = []
    for index in (0, 1):
        with swept_teeth.shared_with(_AloneTwin(index)):
            halves.append(swept_outline(gear, design, driver))
    table = driver_table(design) if gear == GEARS[0] else driven_table(design)
    foot, _, normal = table.at((np.arange(len(whole)) + 0.5) * (table.perimeter / len(whole)))
    first, second = (np.sum((half - foot) * normal, axis=1) for half in halves)
    assert not any(np.allclose(half, whole) for half in halves)
    assert np.array_equal(np.where((first <= second)[:, None], *halves), whole)

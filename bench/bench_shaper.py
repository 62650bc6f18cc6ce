"""Time the shaper path (shaper outline, then the mate swept by it) against the previous point-cloud path.

    python bench/bench_shaper.py

The pairs are the two stages of the five-bar example's planetary train (examples/vegetable_planting.toml:
57 and 77 teeth of module 1.5 in today's design, a 16-tooth shaper), the job that made the shaper path slow. Both paths
run in this process on the same pitch curves: the package's ``shaper_profile`` and ``mate_profile``,
and the previous ones, kept below as the baseline. The baseline densified the cutter (and the cut
driver) to module / 80, placed it every module / 40 along the pitch curve with four linear steps in
between, and kept the smallest radius of the points that fell in each 0.01 deg bin; the package
computes each bin's smallest radius exactly on the segments bounding the swept region.

Besides the times, it prints each path's distance to a converged outline (the package's sweep at
module / 80 with the driver unthinned) and the library's mesh check of each pair. Target: both
stages under 4 s in all, outlines at least as near the converged ones as the baseline's, the
mesh check passing.

The package's cut against its own former envelope and projection is ``bench_teeth.py``.
"""
from __future__ import annotations

import time
from functools import partial
from pathlib import Path
from unittest import mock

import numpy as np
from scipy.spatial import cKDTree

from transplanter import fivebar
from transplanter.gears import swept_teeth
from transplanter.gears.mesh_check import check_mesh
from transplanter.gears.pair import GearPairDesign, driven_angle
from transplanter.gears.pinion_cutter import shaper_cutter
from transplanter.gears.rack_teeth import ADDENDUM, DEDENDUM, PitchTable, orientation
from transplanter.gears.swept_teeth import mate_profile, shaper_profile
from transplanter.gears.teeth import driven_table, driver_table
from transplanter.geometry.poses import rotate_about
from transplanter.trains.toothed_train import design_toothed_train

ROOT = Path(__file__).resolve().parents[1]
ORIGIN = (0.0, 0.0)
BINS = 36000


# --- the previous path (as it was before the exact-segment envelope), the baseline ---

def _by_angle(points):
    angle = np.arctan2(points[:, 1], points[:, 0])
    order = np.argsort(angle)
    return points[order], angle[order]


def _facing(sorted_angle, low, high):
    n = len(sorted_angle)
    start = np.searchsorted(sorted_angle, np.mod(low + np.pi, 2 * np.pi) - np.pi)
    width = int(np.ceil(n * (high - low) / (2 * np.pi))) + 2
    return (start + np.arange(width)) % n


def _swept(points, sorted_angle, facing, reach, place, refine=4):
    chunk = 64
    for start in range(0, len(facing) - 1, chunk):
        rows = np.arange(start, min(start + chunk + 1, len(facing)))
        index = _facing(sorted_angle, facing[rows].min() - reach, facing[rows].max() + reach)
        cloud = place(points[index], rows)
        steps = np.linspace(0, 1, refine, endpoint=False)[None, :, None, None]
        between = cloud[:-1, None] + steps * (cloud[1:, None] - cloud[:-1, None])
        yield between.reshape(-1, 2)


def _binned_envelope(points, tip, chunks):
    bins = np.linspace(-np.pi, np.pi, BINS + 1)
    tip_angle = np.arctan2(tip[:, 1], tip[:, 0])
    order = np.argsort(tip_angle)
    centers = (bins[:-1] + bins[1:]) / 2
    radius = np.interp(centers, tip_angle[order], np.hypot(*tip[order].T), period=2 * np.pi)
    for cloud in chunks:
        bin_of = ((np.arctan2(cloud[:, 1], cloud[:, 0]) + np.pi) * (BINS / (2 * np.pi))).astype(int)
        index = np.minimum(bin_of, BINS - 1)
        np.minimum.at(radius, index, np.hypot(cloud[:, 0], cloud[:, 1]))
    outline = radius[:, None] * np.c_[np.cos(centers), np.sin(centers)]
    return outline if orientation(points) > 0 else outline[::-1]


def _densify(outline, step):
    edges = np.roll(outline, -1, axis=0) - outline
    counts = np.maximum(1, np.ceil(np.linalg.norm(edges, axis=1) / step).astype(int))
    segment = np.repeat(np.arange(len(outline)), counts)
    fraction = (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)) / counts[segment]
    return outline[segment] + fraction[:, None] * edges[segment]


def cloud_shaper_profile(table: PitchTable, module, alpha, cutter_teeth, first_tooth_at=0.0):
    step = module / 40
    radius = module * cutter_teeth / 2
    cutter, cutter_angle = _by_angle(_densify(shaper_cutter(module, alpha, cutter_teeth), step / 2))
    pitch = np.pi * module
    s = np.r_[np.arange(0.0, table.perimeter, step), table.perimeter]
    contact, _, normal = table.at(s)
    center = contact + radius * normal
    psi = np.arctan2(-normal[:, 1], -normal[:, 0])
    turn = np.unwrap(psi) + table.orientation * (s - first_tooth_at - pitch / 2) / radius
    local_facing = np.unwrap(psi) - turn
    reach = 2.5 * (ADDENDUM + DEDENDUM) * module / radius

    def place(points, rows):
        return center[rows, None, :] + rotate_about(points[None], ORIGIN, turn[rows, None])

    tip = table.points + ADDENDUM * module * table.normals
    return _binned_envelope(table.points, tip, _swept(cutter, cutter_angle, local_facing, reach, place))


def cloud_mate_profile(design: GearPairDesign, driver_outline, driven: PitchTable, module):
    step = module / 40
    n1, n2 = design.orders
    outline, outline_angle = _by_angle(_densify(driver_outline, step / 2))
    phi1 = np.r_[np.arange(0.0, 2 * np.pi * n2 / n1, step / design.radius[0].max()), 2 * np.pi * n2 / n1]
    reach = 2.5 * (ADDENDUM + DEDENDUM) * module / design.radius[0].min()
    phi2 = driven_angle(design, phi1)

    def place(points, rows):
        world = rotate_about(points[None], ORIGIN, -phi1[rows, None])
        return rotate_about(world - [design.center_distance, 0.0], ORIGIN, -phi2[rows, None])

    tip = driven.points + ADDENDUM * module * driven.normals
    return _binned_envelope(driven.points, tip, _swept(outline, outline_angle, phi1, reach, place))


# --- the comparison ---

def distance(first, second, spacing=1e-4):
    """Largest distance (mm) from either outline's vertices to the other outline (densified to ``spacing``)."""
    return max(cKDTree(_densify(second, spacing)).query(first)[0].max(),
               cKDTree(_densify(first, spacing)).query(second)[0].max())


def timed(function):
    start = time.perf_counter()
    value = function()
    return time.perf_counter() - start, value


def main():
    result = fivebar.synthesize(fivebar.load_problem(ROOT / "examples/vegetable_planting.toml"))
    gearing = result.problem.gearing
    toothed = design_toothed_train(result.design.relative_angle, result.design.mech.carrier_length, gearing, "bench")
    module, alpha, cutter_teeth = toothed.module, toothed.pressure_angle, gearing.shaper_teeth
    totals = np.zeros(2)
    for name, design, teeth in zip(("stage 1", "stage 2"), (toothed.train.stage_one, toothed.train.stage_two),
                                   toothed.teeth, strict=True):
        if teeth.cutter != "shaper":
            print(f"{name}: rack-cut, not timed")
            continue
        tables = driver_table(design), driven_table(design)
        ours_driver_s, driver = timed(partial(shaper_profile, tables[0], module, alpha, cutter_teeth))
        ours_mate_s, mate = timed(partial(mate_profile, design, driver, tables[1], module))
        old_driver_s, old_driver = timed(partial(cloud_shaper_profile, tables[0], module, alpha, cutter_teeth))
        old_mate_s, old_mate = timed(partial(cloud_mate_profile, design, old_driver, tables[1], module))
        converged = shaper_profile(tables[0], module, alpha, cutter_teeth, step=module / 80)
        with mock.patch.object(swept_teeth, "SIMPLIFY_MODULES", 0.0):
            converged_mate = mate_profile(design, converged, tables[1], module, step=module / 80)
        ours, old = ours_driver_s + ours_mate_s, old_driver_s + old_mate_s
        totals += ours, old
        print(f"{name} ({teeth.counts[0]} teeth, module {module:g}): shaper {ours_driver_s:.2f} s + mate "
              f"{ours_mate_s:.2f} s = {ours:.2f} s; baseline {old_driver_s:.2f} s + {old_mate_s:.2f} s = {old:.2f} s; "
              f"ratio {old / ours:.1f}x")
        print(f"  from the converged outlines (driver, mate): ours {distance(driver, converged):.4f}, "
              f"{distance(mate, converged_mate):.4f} mm; baseline {distance(old_driver, converged):.4f}, "
              f"{distance(old_mate, converged_mate):.4f} mm; ours from baseline {distance(driver, old_driver):.4f}, "
              f"{distance(mate, old_mate):.4f} mm")
        for label, pair in (("ours", (driver, mate)), ("baseline", (old_driver, old_mate))):
            check = check_mesh(design, pair, module)
            print(f"  mesh check, {label}: overlap {check.max_overlap_mm:.4f} mm, contact gap "
                  f"{check.max_contact_gap_mm:.4f} mm, transmission error {check.max_transmission_error_mm:.4f} mm"
                  f" -> {'passes' if check.passed else '; '.join(check.failures)}")
    print(f"both stages: {totals[0]:.2f} s against {totals[1]:.2f} s, ratio {totals[1] / totals[0]:.1f}x; "
          f"target under 4 s")


if __name__ == "__main__":
    main()

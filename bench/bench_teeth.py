"""Time the teeth of the main job's two stages against the former cut, and say how far the former outlines were.

    python bench/bench_teeth.py

The stages are those of the five-bar example's planetary train (examples/vegetable_planting.toml: 57 and 77
shaper-cut teeth of module 1.5 in today's design, a 16-tooth shaper). Both sides run from this process on the
same pitch curves through ``generate_teeth``, both stages as the main job cuts them
(``trains.toothed_train.cut_stages``: here and in a forked side process at once, on Linux with a second core,
each envelope's positions shared between the two; the former cut is patched in before the fork), best of three
each (CPU time: both processes'):

- the package: every point's normal foot converged by Newton's method from where the ray through the gear's
  centre meets the pitch curve; segments cut after all positions are projected, passed over where they stay
  above what their bins already reach;
- the former cut, kept below: the foot from the nearest table sample (a KD tree) and two fixed-point steps
  (not converged), every segment cut chunk by chunk as its positions were projected.

It prints the ratio and both absolute times (target: the package under 1 s wall), the largest distance between
the former and the package's outlines (they share their bins, so this is the height change along the pitch
curve's normal: what a user sees change) on the two stages and on every gear example cut by a shaper, and the
mesh check of the package's stages.
"""
from __future__ import annotations

import os
from functools import partial
from pathlib import Path
from unittest import mock

import numpy as np
from best_time import best_time
from scipy.spatial import cKDTree

from transplanter import fivebar
from transplanter.gears import swept_teeth
from transplanter.gears import synthesis as gear_synthesis
from transplanter.gears.mesh_check import check_mesh
from transplanter.gears.problem import load_problem
from transplanter.gears.rack_teeth import PitchTable
from transplanter.trains.toothed_train import cut_stages, design_toothed_train

ROOT = Path(__file__).resolve().parents[1]
GEAR_EXAMPLES = ("gear_concave_shaper.toml", "gear_cusp_composite.toml")


# --- the former cut (projection and envelope), the baseline ---

def _dot(first, second):
    return first[:, 0] * second[:, 0] + first[:, 1] * second[:, 1]


def former_normal_coordinates(table: PitchTable, samples: cKDTree, points):
    _, nearest = samples.query(points, workers=1)
    offset = points - table.points[nearest]
    s = table.arc[nearest] + _dot(offset, table.tangents[nearest])
    for _ in range(2):
        foot, tangent, normal = table.at(s)
        offset = points - foot
        s = s + _dot(offset, tangent)
    return np.mod(s, table.perimeter), _dot(offset, normal)


def former_cut(at_edge, width, perimeter, ends):
    s_a, h_a, s_b, h_b = ends
    run = np.mod(s_b - s_a + perimeter / 2, perimeter) - perimeter / 2
    back = run < 0
    s_a, h_a, h_b, run = np.where(back, s_b, s_a), np.where(back, h_b, h_a), np.where(back, h_a, h_b), np.abs(run)
    first = np.floor(s_a / width).astype(int)
    crossed = np.floor((s_a + run) / width).astype(int) - first
    some = np.flatnonzero(crossed)
    slope = (h_b[some] - h_a[some]) / run[some]
    s_a, h_a, first, crossed = s_a[some], h_a[some], first[some], crossed[some]
    segment = np.repeat(np.arange(len(some)), crossed)
    edge = np.arange(crossed.sum()) + np.repeat(first + 1 - (np.cumsum(crossed) - crossed), crossed)
    np.minimum.at(at_edge, edge % len(at_edge), h_a[segment] + (edge * width - s_a[segment]) * slope[segment])


def former_polar(points):
    return np.arctan2(points[..., 1], points[..., 0]), points[..., 0] ** 2 + points[..., 1] ** 2


def former_lower_envelope(table, tip_height, module, positions):
    perimeter = table.perimeter
    count = int(np.ceil(perimeter / (swept_teeth.BIN_MODULES * module)))
    width = perimeter / count
    height, at_edge = np.full(count, tip_height), np.full(count, tip_height)
    samples = cKDTree(table.points[:-1])
    tip = table.points + (tip_height + swept_teeth.MARGIN_MODULES * module) * table.normals
    tip_angle, tip_squared = former_polar(tip)
    order = np.argsort(tip_angle)
    for cloud, first_ends, second_ends in positions:
        angle, squared = former_polar(cloud)
        near = squared < np.interp(angle, tip_angle[order], tip_squared[order], period=2 * np.pi)
        grown = swept_teeth._with_segment_ends(near, first_ends, second_ends)
        s, h = np.zeros(near.shape), np.full(near.shape, np.inf)
        s[grown], h[grown] = former_normal_coordinates(table, samples, cloud[grown])
        keep = h < tip_height
        np.minimum.at(height, np.minimum((s[keep] / width).astype(int), count - 1), h[keep])
        at, after = np.unravel_index(first_ends, near.shape), np.unravel_index(second_ends, near.shape)
        cuts = (keep[at] | keep[after]) & grown[at] & grown[after]
        former_cut(at_edge, width, perimeter, (s[at][cuts], h[at][cuts], s[after][cuts], h[after][cuts]))
        cuts = (keep[:-1] | keep[1:]) & grown[:-1] & grown[1:]
        former_cut(at_edge, width, perimeter, (s[:-1][cuts], h[:-1][cuts], s[1:][cuts], h[1:][cuts]))
    return np.minimum(height, np.minimum(at_edge, np.roll(at_edge, -1)))


def former(function):
    """``function()`` with the former envelope patched into the package's profiles."""
    with mock.patch.object(swept_teeth, "_lower_envelope", former_lower_envelope):
        return function()


# --- the comparison ---

def cpu_time(function) -> float:
    """CPU time (s) of one call of ``function()``: this process's and that of the side processes it ended."""
    start = os.times()
    function()
    end = os.times()
    return sum(end[:4]) - sum(start[:4])     # user, system, children's user, children's system


def change(first, second) -> float:
    """Largest distance (mm) between two outlines: vertex by vertex where they are cut on the same bins, else
    from each one's vertices to the other's nearest vertex (a thinned outline's vertices differ)."""
    if first.shape == second.shape:
        return float(np.abs(first - second).max())
    return float(max(cKDTree(second).query(first)[0].max(), cKDTree(first).query(second)[0].max()))


def main():
    result = fivebar.synthesize(fivebar.load_problem(ROOT / "examples/vegetable_planting.toml"))
    gearing = result.problem.gearing
    toothed = design_toothed_train(result.design.relative_angle, result.design.mech.carrier_length, gearing, "bench")
    stages = (toothed.train.stage_one, toothed.train.stage_two)
    cut = partial(cut_stages, stages, toothed.module, toothed.pressure_angle, (toothed.teeth[0].cutter,
                  toothed.teeth[1].cutter), gearing.shaper_teeth, "bench")
    print(f"main job's stages: {toothed.teeth[0].counts} and {toothed.teeth[1].counts} teeth, module "
          f"{toothed.module:g}, cut by {[t.cutter for t in toothed.teeth]}")
    ours_s, ours = best_time(cut, 3)
    old_s, old = best_time(partial(former, cut), 3)
    ours_cpu, old_cpu = cpu_time(cut), cpu_time(partial(former, cut))
    print(f"teeth of both stages, as the main job cuts them (best of 3): package {ours_s:.2f} s wall "
          f"({ours_cpu:.2f} s CPU), "
          f"former {old_s:.2f} s wall ({old_cpu:.2f} s CPU); ratio {old_s / ours_s:.2f}x; target under 1 s")
    for k, (new, previous) in enumerate(zip(ours, old, strict=True)):
        print(f"  stage {k + 1}: former outlines from the package's (driver, driven): "
              f"{change(new.outlines[0], previous.outlines[0]):.2e}, "
              f"{change(new.outlines[1], previous.outlines[1]):.2e} mm")
        check = check_mesh(stages[k], new.outlines, toothed.module)
        print(f"  stage {k + 1} mesh check: overlap {check.max_overlap_mm:.4f} mm, contact gap "
              f"{check.max_contact_gap_mm:.4f} mm, transmission error {check.max_transmission_error_mm:.4f} mm -> "
              f"{'passes' if check.passed else '; '.join(check.failures)}")
    for name in GEAR_EXAMPLES:
        problem = load_problem(ROOT / "examples" / name)
        new_s, new = best_time(partial(gear_synthesis.synthesize, problem), 1)
        previous_s, previous = best_time(partial(former, partial(gear_synthesis.synthesize, problem)), 1)
        print(f"{name}: former outlines from the package's (driver, driven): "
              f"{change(new.teeth.outlines[0], previous.teeth.outlines[0]):.2e}, "
              f"{change(new.teeth.outlines[1], previous.teeth.outlines[1]):.2e} mm; synthesis {new_s:.2f} s against "
              f"{previous_s:.2f} s")


if __name__ == "__main__":
    main()

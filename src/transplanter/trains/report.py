"""The planetary train's part of a report (JSON): its whole-tooth sizes, and the toothed train with its
layout, four gears and the mesh check of both stages."""
from __future__ import annotations

from typing import NamedTuple

import numpy as np

from transplanter.gears.report import mesh_check_json
from transplanter.trains.toothed_train import ToothedTrain, TrainSize


class WorstMesh(NamedTuple):
    """The worse stage's figures of a train's mesh check (mm, degrees)."""

    max_overlap_mm: float
    min_clearance_mm: float
    max_contact_gap_mm: float
    transmission_error_deg: float


def worst_mesh(toothed: ToothedTrain) -> WorstMesh:
    """The largest overlap, smallest clearance, largest contact gap and transmission error of both stages."""
    checks = toothed.mesh
    return WorstMesh(max(c.max_overlap_mm for c in checks), min(c.min_clearance_mm for c in checks),
                     max(c.max_contact_gap_mm for c in checks),
                     max(float(np.degrees(c.max_transmission_error_rad)) for c in checks))


def train_size_json(size: TrainSize) -> dict:
    """Whole-tooth sizes: counts, centre distances (mm), module (mm), cutters, largest pitch radii (mm)."""
    return {"teeth": list(size.counts), "center_distances_mm": list(size.center_distances),
            "module": size.module, "cutters": list(size.cutters),
            "largest_pitch_radius_mm": list(size.largest_pitch_radius)}


def toothed_train_json(toothed: ToothedTrain) -> dict:
    """The toothed train as plain JSON types (mm, degrees): layout, the four gears and the mesh check."""
    a1, a2 = toothed.train.center_distances
    return {
        "layout": toothed.layout, "module": toothed.module,
        "pressure_angle_deg": float(np.degrees(toothed.pressure_angle)),
        "carrier_length_mm": toothed.carrier_length, "center_distances_mm": [a1, a2],
        "teeth": list(toothed.counts), "bend_angle_deg": float(np.degrees(toothed.bend_angle)),
        "shaft_mm": toothed.shaft.tolist(),
        "gears": [{"name": g.name, "role": g.role, "teeth": g.teeth, "module": g.module, "convex": g.convex,
                   "min_curvature_radius_mm": g.min_curvature_radius, "min_concave_radius_mm": g.min_concave_radius,
                   "cutter": g.cutter, "reason": g.reason, "center_mm": g.center.tolist(),
                   "angle_at_turn_zero_deg": float(np.degrees(g.angle_at_turn_zero)), "self_intersections": crossings}
                  for g, crossings in zip(toothed.gears, toothed.self_intersections, strict=True)],
        "mesh_check": {**worst_mesh(toothed)._asdict(), "passed": not toothed.mesh_failures,
                       "failures": toothed.mesh_failures,
                       "stages": [mesh_check_json(check) for check in toothed.mesh]},
        "timings_s": toothed.timings_s,
    }

"""CSV tables of a designed onion transplanter: the Pareto set and the chosen design's field trajectory."""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from transplanter.api_arguments import require_result
from transplanter.output_folder import writable_folder
from transplanter.parallelogram.kinematics import mechanisms
from transplanter.parallelogram.objectives import OBJECTIVES
from transplanter.parallelogram.report import pareto_variables
from transplanter.parallelogram.result import ParallelogramResult
from transplanter.parallelogram.trajectory import sample_path


def write_pareto(result: ParallelogramResult, path: Path) -> Path:
    """``pareto.csv``: rank (1 = knee), the eight variables (mm, alpha in degrees), f1-f3, H, Vx, Y, a."""
    s = result.search
    names = list(pareto_variables(result, 1))
    with path.open("w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(["rank", *names, *OBJECTIVES, "depth_mm", "vx_release_mm_s", "vertical_range_mm",
                         "center_distance_mm"])
        for k in range(len(s.designs)):
            measures = (s.objectives[k], (s.depth[k], s.vx_release[k], s.vertical_range[k], s.center_distance[k]))
            writer.writerow([k + 1, *(f"{value:.10g}" for value in pareto_variables(result, k + 1).values()),
                             *(f"{float(value):.10g}" for values in measures for value in values)])
    return path


def write_trajectory(result: ParallelogramResult, path: Path, samples: int = 721) -> Path:
    """``trajectory.csv``: one driver turn of the final design (polished, else chosen): t (s),
    crank pin A (machine frame, mm), E in the field (mm), its velocity (mm/s) and acceleration (mm/s^2)."""
    p = sample_path(mechanisms(result.problem, result.final), 1, samples)
    table = np.column_stack([p.time, np.degrees(p.driver_angle), *p.crank_pin, *p.tip, *p.velocity, *p.acceleration])
    header = "time_s,driver_angle_deg,ax_mm,ay_mm,ex_mm,ey_mm,vx_mm_s,vy_mm_s,accel_x_mm_s2,accel_y_mm_s2"
    np.savetxt(path, table, delimiter=",", header=header, comments="", fmt="%.10g")
    return path


def write_tables(result: ParallelogramResult, folder: str | Path) -> list[Path]:
    require_result(result, ParallelogramResult, "parallelogram")
    folder = writable_folder(folder)
    return [write_pareto(result, folder / "pareto.csv"), write_trajectory(result, folder / "trajectory.csv")]

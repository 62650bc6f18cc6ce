"""Objectives and constraints of the design (the onion-transplanter paper, section 3.1.1), for a whole population
at once.

- f1 = |Vx(t_E)| (mm/s), f2 = |H - H_target| (mm), f3 = |Y - Y_target| (mm). The printed f3,
  "|Y(X-300}", is garbled; 300 mm is the paper's plant spacing, which none of the eight
  variables changes (spacing = v 2 pi / omega1), so f3 holds the vertical range Y = max - min Y_E
  (the paper's third objective by name) against a target from the file.
- Constraints, each scaled to be about 1 at a violation of the problem's own size, feasible
  where <= 0: the depth band (H_low - H) / H_low and (H - H_high) / H_high; a depth run that
  reaches half a turn (H only bounded); convexity of both pitch curves (the gear library's
  scale-free polynomials); no undercut of either curve at the module (rho_min >= limit).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.parallelogram.gear_checks import gear_margins, undercut_limit
from transplanter.parallelogram.kinematics import mechanisms
from transplanter.parallelogram.problem import ParallelogramProblem
from transplanter.parallelogram.trajectory import TrajectoryMeasures, measure

OBJECTIVES = ("vx_release_abs_mm_s", "depth_error_mm", "vertical_range_error_mm")
CONSTRAINTS = ("depth_above_band_low", "depth_below_band_high", "depth_run_bounded", "driver_convex",
               "driven_convex", "driver_undercut_free", "driven_undercut_free")


@dataclass(frozen=True)
class Scores:
    """Objectives F (P, 3), constraints G (P, 7) (feasible where every G <= 0) and the measures."""

    objectives: np.ndarray
    constraints: np.ndarray
    measures: TrajectoryMeasures
    center_distance: np.ndarray


def score(problem: ParallelogramProblem, variables: dict, samples: int) -> Scores:
    """F and G of every design in ``variables`` (name -> array, mm and rad)."""
    mech = mechanisms(problem, variables)
    m = measure(mech, problem.depth_window, samples)
    gear = gear_margins(mech.m11, mech.m12, mech.amplitude, mech.base_radius, mech.center_distance)
    limit = undercut_limit(problem.module, problem.pressure_angle)
    low, high = problem.depth_band
    objectives = np.column_stack([np.abs(m.vx_release), np.abs(m.depth - problem.depth_target),
                                  np.abs(m.vertical_range - problem.vertical_range_target)])
    constraints = np.column_stack([(low - m.depth) / low, (m.depth - high) / high, np.where(m.window_cut, 1.0, -1.0),
                                   -gear.driver_convexity, -gear.driven_convexity,
                                   (limit - gear.driver_curvature) / limit, (limit - gear.driven_curvature) / limit])
    return Scores(objectives, constraints, m, mech.center_distance)

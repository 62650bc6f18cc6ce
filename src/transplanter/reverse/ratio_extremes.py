"""The least and greatest total ratio i0 = 1 / chi'(c) of an arm motion, found as the extremes of the function,
not of its samples, so that the same path in another frame gives the same range to rounding.

At a touch of a reach circle the rates are 0 / 0 and their rounding error grows as 1 / (distance to it)^2 (about
1e-6 of the ratio at ``TOUCH_LIMIT``), and the ratio may bend sharply there (its slope jumps where the arm folds:
on the rice path by 0.05 per rad). So on each side of a touch the ratio is the cubic through its values at
``TOUCH_STEPS``, which sit far enough from the touch to be exact to about 1e-10; the two sides' limits at the touch
agree to 5e-11 on the rice path. Away from the touches each local
extreme of the reference grid is moved to the vertex of the parabola through it and its neighbours and the ratio
is evaluated there (the value is then off by the square of the vertex's error, far below rounding).
"""
from __future__ import annotations

import numpy as np

from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.arm_inverse import ArmMotion

#: Offsets (rad of path parameter) either side of a touch at which the ratio is taken for its polynomial there.
TOUCH_STEPS = 2e-3 * np.arange(1, 5)
#: The reach of that polynomial either side of the touch: grid points within it are not used.
TOUCH_REACH = TOUCH_STEPS[-1]


def _ratio_at(motion: ArmMotion, x: np.ndarray) -> np.ndarray:
    (c1, _, _), (h1, _, _) = motion.path_rates(np.mod(x, TWO_PI))
    return c1 / h1


def _near_touches(motion: ArmMotion) -> list[np.ndarray]:
    """The ratio over TOUCH_REACH on each side of each touch, densely, from that side's cubic."""
    dense = np.linspace(0.0, TOUCH_REACH, 101)
    found = []
    for touch in motion.touches:
        for side in (-1.0, 1.0):
            values = _ratio_at(motion, touch.parameter + side * TOUCH_STEPS)
            found.append(np.polynomial.Polynomial.fit(TOUCH_STEPS, values, len(TOUCH_STEPS) - 1)(dense))
    return found


def _away_from_touches(motion: ArmMotion) -> np.ndarray:
    """The ratio at the refined local extremes of the grid points farther than TOUCH_REACH from every touch."""
    grid, ratio = motion.grid, motion.total_ratio()
    step = grid[1] - grid[0]
    away = np.ones(len(grid), bool)
    for touch in motion.touches:
        away &= np.abs(np.mod(grid - touch.parameter + np.pi, TWO_PI) - np.pi) > TOUCH_REACH
    before, after = np.roll(ratio, 1), np.roll(ratio, -1)
    extreme = away & np.roll(away, 1) & np.roll(away, -1) & ((ratio - before) * (after - ratio) <= 0)
    bend = before[extreme] - 2 * ratio[extreme] + after[extreme]
    shift = np.where(bend != 0, (before[extreme] - after[extreme]) / np.where(bend != 0, 2 * bend, 1.0), 0.0)
    vertices = grid[extreme] + step * np.clip(shift, -1.0, 1.0)
    return np.r_[ratio[away], _ratio_at(motion, vertices)]


def ratio_range(motion: ArmMotion) -> tuple[float, float]:
    """(least, greatest) i0 over the cycle (module docstring)."""
    values = np.concatenate([_away_from_touches(motion), *_near_touches(motion)])
    return float(values.min()), float(values.max())

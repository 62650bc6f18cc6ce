"""Writes the two reverse-design examples; run from the repository root:

    .venv/bin/python examples/build_reverse_paths.py

Neither paper prints path coordinates, so both paths are made here from a recipe: a loop
swept by tau in [0, 2 pi) at distance rho(tau) = mid - half cos(tau) from the carrier pivot
and direction alpha(tau) = heading + sway sin(tau) + lean sin(2 tau), sampled at 19 values
of tau as the control points of the closed cubic B-spline (the reverse-gear-design paper uses 19). The control
points are then remapped radially about the pivot, r -> a + b r, with (a, b) found by
Newton so that the spline's farthest and nearest points are exactly the targets: the rice-transplanter paper's
Lmax = 254.3 mm and Lmin = 69.7 mm for the rice hoe, and s + l, l - s for the reverse-gear-design paper's
s = 173.88 mm and l = 207.81 mm for the pick-up arm. The distance from the pivot then rises
monotonically from the nearest point to the farthest and back, as the monotonicity criterion
requires (the arm folds at the nearest point and straightens at the farthest).
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from transplanter.geometry.closed_trajectory import ClosedTrajectory

HERE = Path(__file__).resolve().parent


def recipe(heading_deg: float, sway_deg: float, lean_deg: float, farthest: float, nearest: float) -> np.ndarray:
    tau = np.linspace(0, 2 * np.pi, 19, endpoint=False)
    mid, half = (farthest + nearest) / 2, (farthest - nearest) / 2
    rho = mid - half * np.cos(tau)
    alpha = np.radians(heading_deg + sway_deg * np.sin(tau) + lean_deg * np.sin(2 * tau))

    def points(a, b):
        r = a + b * rho
        return np.c_[r * np.cos(alpha), r * np.sin(alpha)]

    def miss(ab):
        radii = [e.radius for e in ClosedTrajectory(points(*ab)).radial_extremes()]
        return np.array([max(radii) - farthest, min(radii) - nearest])

    ab = np.array([0.0, 1.0])
    for _ in range(20):
        if np.abs(miss(ab)).max() < 1e-11:
            break
        jacobian = np.column_stack([(miss(ab + step) - miss(ab)) / 1e-7 for step in np.eye(2) * 1e-7])
        ab = ab - np.linalg.solve(jacobian, miss(ab))
    assert np.abs(miss(ab)).max() < 1e-9, miss(ab)
    return points(*ab)


def toml_points(points: np.ndarray) -> str:
    return "[\n" + "".join(f"    [{float(x)!r}, {float(y)!r}],\n" for x, y in points) + "]"


RICE_TITLE = "Rice transplanter hoe path, the rice-transplanter paper (Lmax 254.3 mm, Lmin 69.7 mm), four-gear train"
RICE = '''title = "{title}"
description = """
A loop hanging below the gear box, made by examples/build_reverse_paths.py (the rice-transplanter paper prints
no coordinates). The arm lengths are left out, so they come from the path's farthest and
nearest points by the rice-transplanter paper eq (1-2): s = 92.3 mm, l = 162 mm."""

[trajectory]
kind = "control_points"
points = {points}

[arm]
pivot = [0.0, 0.0]
direction = "clockwise"

[train]
topology = "sun-intermediate-planet"
split = "sqrt"
module = 2.0
'''

PICKUP_TITLE = ("Seedling pick-up arm, the reverse-gear-design paper (s = 173.88 mm, l = 207.81 mm), "
                "bent carrier of the cusp-pitch-curve paper eq (15)")
PICKUP = '''title = "{title}"
description = """
A loop reaching from next to the carrier pivot out to s + l, made by
examples/build_reverse_paths.py (the reverse-gear-design paper prints no coordinates). Four gears on a bent
carrier (L1 = L2 = 90 mm), split by the peak-to-valley coefficient, module 2.53 mm (the reverse-gear-design paper)."""

[trajectory]
kind = "control_points"
points = {points}

[arm]
pivot = [0.0, 0.0]
carrier_length = 173.88
arm_length = 207.81
direction = "counterclockwise"

[train]
topology = "pick-up"
split = "peak_to_valley"
peak_to_valley = 0.6
center_distances = [90.0, 90.0]
module = 2.53
'''


def main():
    rice = recipe(-90.0, 16.0, 5.0, 254.3, 69.7)
    (HERE / "rice_hoe_reverse.toml").write_text(RICE.format(title=RICE_TITLE, points=toml_points(rice)))
    carrier, arm = 173.88, 207.81       # the reverse-gear-design paper's s and l
    pickup = recipe(-120.0, 22.0, 6.0, carrier + arm, arm - carrier)
    (HERE / "pickup_arm_reverse.toml").write_text(PICKUP.format(title=PICKUP_TITLE, points=toml_points(pickup)))


if __name__ == "__main__":
    main()

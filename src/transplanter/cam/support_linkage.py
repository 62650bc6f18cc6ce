"""The rocker-slider of the seedling-support mechanism of Wang et al. 2025 (Figure 11, eq 14-15).

The oscillating bar turns about C; its arm C-G carries the rod G-H, whose end H is the top of the
support plate H-Z sliding vertically at x = x_Z. Eq (14) chains C -> G -> H with H = (x_Z, y_Z + l_HZ);
with theta_GH eliminated the loop is P + Q cos(theta_CG) + R sin(theta_CG) = 0 (derivations/cam_support.py),
solved here for both assemblies. Eq (15): the swing between the plate's two extreme heights is
psi = theta_CG1 - theta_CG2.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.cam_support import support_rocker_parts
from transplanter.cam.kinematics import group
from transplanter.generated import numpy_twin

#: Assemblies: the sign in theta_CG = atan2(R, Q) +- acos(-P / sqrt(Q^2 + R^2)).
ASSEMBLIES = (1, -1)


@dataclass(frozen=True)
class SupportLinkage:
    """The rocker-slider in mm and radians.

    Attributes
    ----------
    pivot : ndarray (2,)
        C, the oscillating bar's pivot.
    rocker_length, rod_length, plate_length : float
        l_CG, l_GH, l_HZ.
    plate_x : float
        x_Z, the line the plate slides on.
    plate_below_rod : bool
        False: H = Z + (0, l_HZ), eq (14) as printed; True: H = Z - (0, l_HZ).
    """

    pivot: np.ndarray
    rocker_length: float
    rod_length: float
    plate_length: float
    plate_x: float
    plate_below_rod: bool = False

    def slider_point(self, plate_height) -> np.ndarray:
        """H (..., 2) for the plate's point Z at height ``plate_height`` (mm)."""
        height = np.asarray(plate_height, float)
        side = -1.0 if self.plate_below_rod else 1.0
        return np.stack(np.broadcast_arrays(self.plate_x, height + side * self.plate_length), -1)

    def reach(self) -> tuple[float, float]:
        """Distances |C - H| (mm) at which the chain C-G-H closes: |l_CG - l_GH| to l_CG + l_GH."""
        return abs(self.rocker_length - self.rod_length), self.rocker_length + self.rod_length

    def rocker_angles(self, plate_height) -> np.ndarray:
        """theta_CG (rad) of each assembly (``ASSEMBLIES``), shape (2, ...); NaN where the chain cannot close."""
        h = self.slider_point(plate_height)
        (p, q, r), = numpy_twin(support_rocker_parts)(
            group(*self.pivot, self.rocker_length, self.rod_length), np.moveaxis(h, -1, 0))
        ratio = -p / np.hypot(q, r)
        spread = np.arccos(np.where(np.abs(ratio) <= 1, ratio, np.nan))
        return np.stack([np.arctan2(r, q) + sign * spread for sign in ASSEMBLIES])

    def joint_g(self, rocker_angle) -> np.ndarray:
        """G (..., 2) for the rocker at ``rocker_angle`` (rad)."""
        angle = np.asarray(rocker_angle, float)
        return self.pivot + self.rocker_length * np.stack([np.cos(angle), np.sin(angle)], -1)

    def plate_height(self, rocker_angle, above: float) -> np.ndarray:
        """y_Z (mm) for the rocker at ``rocker_angle`` (rad): eq (14) solved for the slider, with H above G
        (``above`` = 1) or below it (-1); NaN where G-H cannot reach the line x = x_Z."""
        g = self.joint_g(rocker_angle)
        span = self.rod_length**2 - (self.plate_x - g[..., 0]) ** 2
        h = g[..., 1] + above * np.sqrt(np.where(span >= 0, span, np.nan))
        return h - (-1.0 if self.plate_below_rod else 1.0) * self.plate_length

    def closure_residual(self, plate_height, rocker_angle) -> np.ndarray:
        """|G - H| - l_GH (mm): an independent check of a solved rocker angle (zero when the loop closes)."""
        return np.linalg.norm(self.joint_g(rocker_angle) - self.slider_point(plate_height), axis=-1) - self.rod_length


@dataclass(frozen=True)
class SupportSwing:
    """The rocker between the plate's low and high heights, per assembly (eq 15).

    Attributes
    ----------
    low_angle, high_angle : ndarray (2,)
        theta_CG1 (plate low, start of pushing) and theta_CG2 (plate high), rad; NaN where it cannot assemble.
    swing : ndarray (2,)
        psi = theta_CG1 - theta_CG2 (rad), wrapped to (-pi, pi].
    residual_mm : float
        Largest |G - H| - l_GH over the solved angles.
    """

    low_angle: np.ndarray
    high_angle: np.ndarray
    swing: np.ndarray
    residual_mm: float


def support_swing(linkage: SupportLinkage, low_height: float, high_height: float) -> SupportSwing:
    """Solve eq (14) at the plate's two heights and the swing of eq (15), both assemblies."""
    low, high = linkage.rocker_angles(low_height), linkage.rocker_angles(high_height)
    swing = np.angle(np.exp(1j * (low - high)))
    residuals = [linkage.closure_residual(h, a) for h, angles in ((low_height, low), (high_height, high))
                 for a in angles if np.isfinite(a)]
    return SupportSwing(low, high, swing, float(np.abs(residuals).max()) if residuals else float("nan"))

"""One pair of external non-circular gears from a driver pitch curve.

Closure (the onion-transplanter paper, eq 5): the driven gear turns 2 pi n1 / n2 per driver turn,
    int_0^2pi r1 / (a - r1) dphi1 = 2 pi n1 / n2,
solved for the center distance a (the left side falls monotonically from +inf at
a = max r1 to 0). The driven curve, curvature (eq 8), ratio and kinematics (eq 13-15) come
from the generated ``gears`` functions. Integrals use Gauss-Legendre panels split at the
curve's breaks, so piecewise curves are integrated piece by piece.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.gears import conjugate_pitch, pair_kinematics, polar_curvature
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.gears.pitch_curves import PitchCurve, too_small_radius
from transplanter.generated import numpy_twin
from transplanter.geometry.hermite import hermite
from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.turn_quadrature import NODES, PANELS, Panels, panels

_conjugate = numpy_twin(conjugate_pitch)
_curvature = numpy_twin(polar_curvature)
_kinematics = numpy_twin(pair_kinematics)

def arc_length(curve: PitchCurve, grid: Panels) -> np.ndarray:
    """Arc length of the pitch curve from phi = 0 to every panel edge: int sqrt(r^2 + r'^2) dphi (mm)."""
    return grid.integrate(np.hypot(*curve.evaluate(grid.nodes)[:2]))


def driven_turn(curve: PitchCurve, center_distance: float, grid: Panels) -> float:
    """Driven rotation per driver turn: int r1 / (a - r1) dphi1."""
    r = curve.evaluate(grid.nodes)[0]
    return float(grid.integrate(r / (center_distance - r))[-1])


def closing_center_distance(r: np.ndarray, orders: tuple[int, int], grid: Panels, r_max: float) -> float:
    """Center distance (mm) for the driven gear to turn 2 pi n1 / n2 per driver turn (Newton with
    bisection), from the driver radius ``r`` (mm) at the nodes of ``grid``."""
    target = TWO_PI * orders[0] / orders[1]

    def residual(a):
        gap = a - r
        return grid.integrate(r / gap)[-1] - target, -grid.integrate(r / gap**2)[-1]

    low, high = r_max * (1 + 1e-9), 2 * r_max
    while residual(high)[0] > 0:
        low, high = high, 2 * high
    a = high
    for _ in range(100):
        value, derivative = residual(a)
        if abs(value) <= 1e-15 * target:
            break
        low, high = (a, high) if value > 0 else (low, a)
        step = a - value / derivative
        a = step if low < step < high else (low + high) / 2
    return a


@dataclass(frozen=True)
class GearPairDesign:
    """Both pitch curves sampled at the panel edges of one driver turn, and what follows from them."""

    driver: PitchCurve
    orders: tuple[int, int]
    center_distance: float
    closure_error: float
    phi1: np.ndarray            # driver polar angle of the contact point (rad)
    phi2: np.ndarray            # driven rotation (rad), 0 at phi1 = 0
    radius: tuple[np.ndarray, np.ndarray]
    curvature_radius: tuple[np.ndarray, np.ndarray]
    convexity: tuple[np.ndarray, np.ndarray]
    ratio: np.ndarray           # i12 = omega1 / omega2
    driven_speed: np.ndarray    # rad/s for the driver speed
    driven_acceleration: np.ndarray
    driver_speed: float
    perimeters: tuple[float, float]
    rolling_mismatch_mm: float
    joints: list[dict]
    points: tuple[np.ndarray, np.ndarray]  # driver curve; driven curve in its frame (contact at angle pi - phi2)
    arc: np.ndarray                        # arc length run off both curves from phi1 = 0
    driven_slope: np.ndarray               # dr2/dphi2


def arc_lengths(points: np.ndarray) -> np.ndarray:
    """Arc length from the first point to every other point of a polyline, Richardson-extrapolated
    from the full and the every-other-point polylines (error O(h^4) on a smooth curve)."""
    fine = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(points, axis=0), axis=1))][::2]
    coarse = np.r_[0.0, np.cumsum(np.linalg.norm(np.diff(points[::2], axis=0), axis=1))]
    return (4 * fine - coarse) / 3


def _joint_report(curve: PitchCurve) -> list[dict]:
    """Jumps of r, r' and r'' across each joint (one-sided values 1e-7 rad away, extrapolated)."""
    out = []
    for joint in curve.joints:
        eps = 1e-7
        left = curve.evaluate(np.array([joint - eps]))
        right = curve.evaluate(np.array([joint + eps]))
        # first-order extrapolation of r and r' to the joint from each side
        r_left, r_right = left[0][0] + eps * left[1][0], right[0][0] - eps * right[1][0]
        s_left, s_right = left[1][0] + eps * left[2][0], right[1][0] - eps * right[2][0]
        out.append({"phi_deg": float(np.degrees(joint)), "radius_jump": float(r_right - r_left),
                    "slope_jump": float(s_right - s_left), "bend_jump": float(right[2][0] - left[2][0])})
    return out


def design_pair(driver: PitchCurve, driven_order: int, center_distance: float | None = None,
                driver_speed: float = TWO_PI, source: str = "<gear>", where: str = "driver") -> GearPairDesign:
    """The pair of ``driver`` and its driven curve of ``driven_order`` at ``center_distance`` (None: the closing
    one); ``where`` names the driver's table in the messages of a refused curve."""
    grid = panels(driver.breaks)
    dense = np.linspace(0, TWO_PI, 20001)
    r_dense = driver.evaluate(dense)[0]
    if not np.all(np.isfinite(r_dense)) or r_dense.min() <= 0:
        k = int(np.argmin(np.where(np.isfinite(r_dense), r_dense, -np.inf)))
        raise ProblemError(f"{source}: {where}: the pitch radius reaches {r_dense[k]:.6g} mm at phi = "
                           f"{np.degrees(dense[k]):.2f} deg: expected a positive radius all round")
    r_max = float(r_dense.max())
    defect = too_small_radius(dense, r_dense, r_max)
    if defect:
        raise ProblemError(f"{source}: {where}: {defect}, or the ratio leaves the thousandfold range (a shape "
                           "parameter too near its limit, e.g. an eccentricity near 1)")
    orders = (driver.lobes, driven_order)
    r_nodes, slope_nodes, _ = driver.evaluate(grid.nodes)
    given = center_distance is not None
    if center_distance is None:
        center_distance = closing_center_distance(r_nodes, orders, grid, r_max)
    elif center_distance <= r_max:
        raise ProblemError(f"{source}: pair.center_distance = {center_distance:g}: expected more than the largest "
                           f"driver radius {r_max:.6g} mm (the driven radius a - r1 would reach zero)")
    target = TWO_PI * orders[0] / orders[1]
    check = panels(driver.breaks, count=2 * PANELS + 17, nodes=NODES + 4)
    closure_error = driven_turn(driver, center_distance, check) - target
    if abs(closure_error) > 1e-6:
        closing = closing_center_distance(r_nodes, orders, grid, r_max)
        if not given or abs(closing - center_distance) <= 1e-9 * center_distance:
            raise InfeasibleError(
                f"{source}: {where}: the pitch curve varies too fast for the turn quadrature ({PANELS} panels): at "
                f"its closing center distance {closing:.9f} mm a finer quadrature turns the driven gear "
                f"{np.degrees(closure_error + target):.6f} deg per driver turn instead of {np.degrees(target):.6f}; "
                f"use a smoother curve (a smaller eccentricity, order or ratio range)")
        raise InfeasibleError(
            f"{source}: pair.center_distance = {center_distance:g} mm does not close with orders {orders}: the driven "
            f"gear turns {np.degrees(closure_error + target):.6f} deg per driver turn instead of "
            f"{np.degrees(target):.6f}; the closing center distance is {closing:.9f} mm: give that, or leave "
            "pair.center_distance out to have it found")

    phi1 = grid.edges
    r1, slope1, bend1 = driver.evaluate(phi1)
    phi2 = grid.integrate(r_nodes / (center_distance - r_nodes))
    a = np.full_like(r1, center_distance)
    r2, slope2, bend2, _ = (v[0] for v in _conjugate([a], [r1], [slope1], [bend1]))
    with np.errstate(divide="ignore", invalid="ignore"):   # rho is infinite where a curve is straight
        rho1, convex1 = (v[0] for v in _curvature([r1], [slope1], [bend1]))
        rho2, convex2 = (v[0] for v in _curvature([r2], [slope2], [bend2]))
    ratio, speed, acceleration = (v[0] for v in _kinematics([a], [r1], [slope1], [np.full_like(r1, driver_speed)]))

    arc = grid.integrate(np.hypot(r_nodes, slope_nodes))     # arc_length without evaluating the nodes again
    driver_perimeter = float(arc[-1])
    driver_points = r1[:, None] * np.c_[np.cos(phi1), np.sin(phi1)]
    driven_points = r2[:, None] * np.c_[-np.cos(phi2), np.sin(phi2)]
    mismatch = np.abs(arc_lengths(driver_points) - arc_lengths(driven_points)).max()
    return GearPairDesign(
        driver=driver, orders=orders, center_distance=float(center_distance), closure_error=float(closure_error),
        phi1=phi1, phi2=phi2, radius=(r1, r2), curvature_radius=(rho1, rho2), convexity=(convex1, convex2),
        ratio=ratio, driven_speed=speed, driven_acceleration=acceleration, driver_speed=driver_speed,
        perimeters=(driver_perimeter, driver_perimeter * orders[1] / orders[0]),
        rolling_mismatch_mm=float(mismatch), joints=_joint_report(driver),
        points=(driver_points, driven_points), arc=arc, driven_slope=slope2)


def arc_to_angle(design: GearPairDesign, arc) -> np.ndarray:
    """phi1 (rad) at driver pitch arc ``arc`` (mm, taken modulo the perimeter), cubic Hermite on the design's samples
    with dphi/ds = 1 / sqrt(r^2 + r'^2) at both ends of each interval, taken just inside it (a corner's two sides).
    Linear interpolation made the rolling contact run at a speed 1 % off along a sample interval of the chord, and an
    arch rolled on it missed its normal by 0.015 mm."""
    grid = design.phi1
    inside = 1e-9 * (grid[1:] - grid[:-1])
    start_rate, end_rate = (1 / np.hypot(*design.driver.evaluate(ends)[:2])
                            for ends in (grid[:-1] + inside, grid[1:] - inside))
    return hermite(design.arc, grid, start_rate, end_rate, np.mod(np.asarray(arc, float), design.perimeters[0]))


def driven_angle(design: GearPairDesign, phi1: np.ndarray) -> np.ndarray:
    """phi2 at any driver angle (unwrapped over turns), cubic Hermite on the design's samples."""
    turn = 2 * np.pi * design.orders[0] / design.orders[1]
    laps = np.floor(phi1 / (2 * np.pi))
    slope = design.radius[0] / (design.center_distance - design.radius[0])
    return hermite(design.phi1, design.phi2, slope[:-1], slope[1:], phi1 - 2 * np.pi * laps) + laps * turn

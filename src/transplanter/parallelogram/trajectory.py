"""What the field trajectory of the planting point gives (the onion-transplanter paper, section 3.1.1), for many
designs at once.

- Planting instant t_E: the lowest point of E over one driver turn. Found on a grid of the turn,
  then refined by Newton steps (kept in the bracket) on the exact vertical velocity.
- Vx(t_E): the exact horizontal field velocity at that instant (f1 = |Vx|).
- Planting depth H: the vertical extent of the stretch of path around the lowest point on which
  |X_E - X_E(t_E)| <= w (w = 0.5 mm in the paper). Computed robustly: the stretch is the
  connected run of a grid of one turn centred on t_E where the condition holds, its two ends
  are refined by bracketed Newton steps on the exact X_E, and H is the largest height on the run (grid and
  ends) above the lowest point. A run that reaches half a turn either side is cut there.
- Vertical range Y = max Y_E - min Y_E (both extremes refined): 2 l1 whenever the crank turns fully.
- Plant spacing: the machine's travel per crank turn, |v| 2 pi / omega1 * 2 pi / phi2(2 pi)
  (|v| T for a closed pair; none of the eight variables changes it).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.planar import TWO_PI
from transplanter.parallelogram.kinematics import Mechanisms

SAMPLES = 1024          # grid points per turn
NEWTON_STEPS = 60


@dataclass(frozen=True)
class TrajectoryMeasures:
    """One value per design (shape (P,)); mm, mm/s, rad, s."""

    planting_angle: np.ndarray      # phi1 at t_E, in [0, 2 pi)
    planting_time: np.ndarray
    lowest: np.ndarray              # (2, P) X_E, Y_E at t_E
    vx_release: np.ndarray
    vy_release: np.ndarray
    ax_release: np.ndarray
    ay_release: np.ndarray
    depth: np.ndarray
    window: np.ndarray              # (2, P) phi1 at the two ends of the depth run
    window_cut: np.ndarray          # bool: the run reached half a turn (H is then a lower bound)
    vertical_range: np.ndarray
    spacing: np.ndarray


def _root(function, low: np.ndarray, high: np.ndarray, steps: int = NEWTON_STEPS) -> np.ndarray:
    """Per design, a root of ``function`` (returning value and slope) bracketed by ``low`` and ``high``:
    Newton steps kept inside the bracket, bisection where a step would leave it or would not halve
    the Newton step before (a kink, e.g. the gear's joint). A design stops once its Newton step is
    below 1e-12 rad."""
    f_low = function(low)[0]
    x = 0.5 * (low + high)
    last = np.full_like(x, np.inf)      # the previous Newton step (inf after a bisection)
    for _ in range(steps):
        value, slope = function(x)
        with np.errstate(divide="ignore", invalid="ignore"):
            delta = value / slope
        done = np.abs(delta) <= 1e-12
        if np.all(done):
            break
        left = np.sign(value) == np.sign(f_low)
        low, f_low = np.where(left, x, low), np.where(left, value, f_low)
        high = np.where(left, high, x)
        step = x - delta
        inside = (np.isfinite(step) & (step > np.minimum(low, high)) & (step < np.maximum(low, high))
                  & (np.abs(delta) <= 0.5 * last))
        last = np.where(inside, np.abs(delta), np.inf)
        x = np.where(done, x, np.where(inside, step, 0.5 * (low + high)))
    return x


def _extreme(mech: Mechanisms, grid: np.ndarray, heights: np.ndarray, lowest: bool) -> np.ndarray:
    """Driver angle of the lowest (or highest) point: grid extreme, then V_y = 0 (slope A_y / omega1)."""
    k = np.argmin(heights, axis=1) if lowest else np.argmax(heights, axis=1)
    step = grid[1] - grid[0]
    low = np.maximum(grid[k] - step, 0.0)
    high = np.minimum(grid[k] + step, TWO_PI)

    def vertical_speed(phi):
        _, _, velocity, acceleration = mech.state(phi)
        return velocity[1], acceleration[1] / mech.driver_speed

    return _root(vertical_speed, low, high)


def _turn_around(mech: Mechanisms, grid: np.ndarray, positions: np.ndarray, bottom: np.ndarray):
    """Driver angles of a turn centred on the grid point nearest ``bottom`` (the exact bottom is the centre
    when the pair does not close) and E there in the machine's frame. A closed pair repeats every turn,
    so the grid's own positions are reused, shifted by whole turns."""
    samples = grid.size
    steps = np.arange(-(samples // 2), samples - samples // 2 + 1)
    if np.all(np.abs(mech.driven_turn - TWO_PI) <= 1e-9 * TWO_PI):
        nearest = np.rint(bottom / (grid[1] - grid[0])).astype(int)
        index = nearest[:, None] + steps[None, :]
        wrapped = np.mod(index, samples)
        rows = np.arange(mech.count)[:, None]
        return grid[wrapped] + TWO_PI * np.floor_divide(index, samples), positions[:, rows, wrapped]
    around = bottom[:, None] + steps[None, :] * (grid[1] - grid[0])
    return around, mech.position(around)


def _gap(mech: Mechanisms, phi: np.ndarray, x_bottom: np.ndarray, window: float):
    """|X_E - X_E(t_E)| - w and its slope in phi1."""
    _, tip, velocity, _ = mech.state(phi)
    offset = tip[0] - x_bottom
    return np.abs(offset) - window, np.sign(offset) * velocity[0] / mech.driver_speed


def measure(mech: Mechanisms, window: float, samples: int = SAMPLES) -> TrajectoryMeasures:
    """Planting instant, Vx there, depth H (window ``window`` mm), Y and spacing of every design."""
    count = mech.count
    grid = np.linspace(0.0, TWO_PI, samples, endpoint=False)
    positions = mech.position(np.broadcast_to(grid, (count, samples)))
    bottom = _extreme(mech, grid, positions[1], lowest=True)
    top = _extreme(mech, grid, positions[1], lowest=False)
    _, at_bottom, velocity, acceleration = mech.state(bottom)
    height_top = mech.state(top)[1][1]

    around, relative = _turn_around(mech, grid, positions, bottom)
    path = relative + np.array([mech.forward_velocity / mech.driver_speed, 0.0])[:, None, None] * around
    inside = np.abs(path[0] - at_bottom[0][:, None]) <= window
    centre = samples // 2
    inside[:, centre] = True
    left = np.cumprod(inside[:, centre::-1], axis=1).sum(axis=1)      # run length from the centre, leftwards
    right = np.cumprod(inside[:, centre:], axis=1).sum(axis=1)
    last_left, last_right = centre - (left - 1), centre + (right - 1)
    cut = (last_left == 0) | (last_right == samples)
    rows = np.arange(count)
    ends = []
    for last, outward in ((last_left, -1), (last_right, 1)):
        beyond = np.clip(last + outward, 0, samples)
        crossing = _root(lambda phi: _gap(mech, phi, at_bottom[0], window), around[rows, last], around[rows, beyond])
        ends.append(np.where(beyond == last, around[rows, last], crossing))
    columns = np.arange(samples + 1)[None, :]
    on_run = (columns >= last_left[:, None]) & (columns <= last_right[:, None])
    run_top = np.max(np.where(on_run, path[1], -np.inf), axis=1)
    end_heights = [mech.state(e)[1][1] for e in ends]
    depth = np.maximum(run_top, np.maximum(*end_heights)) - at_bottom[1]
    spacing = abs(mech.forward_velocity) * TWO_PI / mech.driver_speed * TWO_PI / mech.driven_turn
    return TrajectoryMeasures(
        planting_angle=bottom, planting_time=bottom / mech.driver_speed, lowest=at_bottom,
        vx_release=velocity[0], vy_release=velocity[1], ax_release=acceleration[0], ay_release=acceleration[1],
        depth=depth, window=np.array(ends), window_cut=cut, vertical_range=height_top - at_bottom[1],
        spacing=spacing)


@dataclass(frozen=True)
class SampledPath:
    """One design's motion over whole driver turns: time (s), crank pin A (machine frame), E in
    the field, its velocity and acceleration, each (2, n) in mm, mm/s, mm/s^2."""

    time: np.ndarray
    driver_angle: np.ndarray
    crank_pin: np.ndarray
    tip: np.ndarray
    velocity: np.ndarray
    acceleration: np.ndarray


def sample_path(mech: Mechanisms, turns: float = 1.0, samples: int = 721, start: float = 0.0) -> SampledPath:
    """The first design of ``mech`` over ``turns`` driver turns from driver angle ``start``."""
    phi = start + np.linspace(0.0, TWO_PI * turns, samples)[None, :]
    pin, tip, velocity, acceleration = (s[:, 0] for s in mech.first().state(phi))
    return SampledPath(phi[0] / mech.driver_speed, phi[0], pin, tip, velocity, acceleration)

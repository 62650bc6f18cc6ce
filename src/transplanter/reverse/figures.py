"""Figures of a reverse design: the path with the arm (target against reproduced), the angles and
ratios along the cycle, and the pitch curves on the carrier."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from transplanter.geometry.closed_trajectory import TWO_PI  # noqa: E402
from transplanter.reverse.idler_train import IdlerTrain  # noqa: E402
from transplanter.reverse.synthesis import ReverseResult  # noqa: E402
from transplanter.trains.figures import draw_four_gear_train  # noqa: E402


def plot_path(result: ReverseResult, path: str):
    motion, pivot = result.motion, result.problem.pivot
    x = np.linspace(0, TWO_PI, 2000)
    curve = result.trajectory.evaluate(x) + pivot
    fig, ax = plt.subplots(figsize=(7, 7))
    ring = np.linspace(0, TWO_PI, 400)
    for radius, style in ((motion.carrier_length + motion.arm_length, "c--"),
                          (abs(motion.carrier_length - motion.arm_length), "c:")):
        ax.plot(pivot[0] + radius * np.cos(ring), pivot[1] + radius * np.sin(ring), style, lw=0.8)
    ax.plot(*curve.T, "k-", lw=1.2, label="target path")
    ax.plot(*(result.problem.points + pivot).T, "o", mfc="none", color="0.5", ms=4, label=result.problem.kind)
    for violation in result.violations:
        if violation.condition != "turns":
            span = np.linspace(violation.u_start, violation.u_end + (violation.u_end < violation.u_start), 100)
            ax.plot(*(result.trajectory.evaluate(TWO_PI * span) + pivot).T, "r-", lw=3)
    for touch in motion.touches:
        ax.plot(*(result.trajectory.evaluate(touch.parameter) + pivot), "ms")
    if result.verification is not None:
        ax.plot(*(result.verification.reproduced[::40] + pivot).T, "g.", ms=3,
                label=f"rolled gears (max miss {result.verification.max_error_mm:.1e} mm)")
    for x0 in np.linspace(0, TWO_PI, 8, endpoint=False):
        theta, gamma = motion.angles(np.array([x0]))
        elbow = pivot + motion.carrier_length * np.array([np.cos(theta[0]), np.sin(theta[0])])
        tip = result.trajectory.evaluate(x0) + pivot
        ax.plot(*np.array([pivot, elbow, tip]).T, "-", color="tab:blue", lw=0.8, alpha=0.6)
    ax.plot(*pivot, "k+", ms=10)
    ax.set_aspect("equal")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title("path, reach circles (cyan), touches (magenta), violations (red)", fontsize=9)
    ax.legend(fontsize=8)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_motion(result: ReverseResult, path: str):
    motion = result.motion
    x = motion.grid
    theta, gamma = motion.angles(x)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 7))
    top.plot(x / TWO_PI, np.degrees(theta - theta[0]), label="carrier theta - theta(0)")
    top.plot(x / TWO_PI, np.degrees(gamma - gamma[0]), label="arm against carrier gamma - gamma(0)")
    top.set_xlabel("path parameter u")
    top.set_ylabel("deg")
    top.legend(fontsize=8)
    if result.train is not None:
        c = result.verification.carrier_turns
        bottom.plot(np.degrees(c), 1 / result.relative.evaluate(c, 1), "k", label="total i0 (sun : planet)")
        if not isinstance(result.train, IdlerTrain):
            first, second = result.train.stage_ratios(c)
            bottom.plot(np.degrees(c), first, label="stage 1 (sun : intermediate)")
            bottom.plot(np.degrees(c), second, label="stage 2 (intermediate : planet)")
        bottom.set_xlabel("carrier turn c (deg)")
        bottom.set_ylabel("transmission ratio")
        bottom.legend(fontsize=8)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_gears(result: ReverseResult, path: str):
    train = result.train
    fig, ax = plt.subplots(figsize=(8, 6))
    if isinstance(train, IdlerTrain):
        a = train.center_distance
        driver, idler = train.stage_one.points
        ax.plot(*driver.T, label="sun")
        ax.plot(*(idler + [a, 0]).T, label="idler")
        ax.plot(*(train.stage_two.points[1] + [2 * a, 0]).T, label="planet (conjugate of the idler's far side)")
        for center in (0, a, 2 * a):
            ax.plot(center, 0, "k+")
        ax.set_aspect("equal")
        ax.legend(fontsize=7)
    else:
        draw_four_gear_train(ax, train, result.motion.carrier_length)
    ax.set_title(f"pitch curves on the carrier: {result.problem.topology}", fontsize=9)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_reverse_figures(result: ReverseResult, out: Path) -> list[str]:
    out.mkdir(parents=True, exist_ok=True)
    figures = {"path.png": plot_path, "motion.png": plot_motion}
    if result.train is not None:
        figures["gears.png"] = plot_gears
    for name, plot in figures.items():
        plot(result, str(out / name))
    return list(figures)

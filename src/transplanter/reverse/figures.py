"""Figures of a reverse design: the path with the arm (target against reproduced), the angles and
ratios along the cycle, and the pitch curves on the carrier, as matplotlib ``Figure`` objects (no
pyplot, no backend chosen: a notebook shows them, the command saves them)."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.figure_conventions import LEGEND_BESIDE, FigureDrawer, drawn
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.idler_train import IdlerTrain
from transplanter.reverse.result import ReverseResult
from transplanter.trains.figures import draw_four_gear_train


def draw_path(result: ReverseResult) -> Figure:
    """The target path, reach circles, touches, violations, the arm at eight places and the tip
    rebuilt from the rolled gears (mm)."""
    motion, pivot = result.motion, result.problem.pivot
    x = np.linspace(0, TWO_PI, 2000)
    curve = result.trajectory.evaluate(x) + pivot
    fig = Figure(figsize=(9.5, 7), layout="constrained")
    ax = fig.subplots()
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
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    return fig


def draw_motion(result: ReverseResult) -> Figure:
    """Carrier and arm angles along the path (deg), and the transmission ratios against the carrier turn."""
    motion = result.motion
    x = motion.grid
    theta, gamma = motion.angles(x)
    fig = Figure(figsize=(10, 7), layout="constrained")
    top, bottom = fig.subplots(2, 1)
    top.plot(x / TWO_PI, np.degrees(theta - theta[0]), label="carrier theta - theta(0)")
    top.plot(x / TWO_PI, np.degrees(gamma - gamma[0]), label="arm against carrier gamma - gamma(0)")
    top.set_xlabel("path parameter u (turns)")
    top.set_ylabel("angle (deg)")
    top.legend(fontsize=8, **LEGEND_BESIDE)
    verification, relative = result.verification, result.relative
    if result.train is not None and verification is not None and relative is not None:    # all three, or none
        c = verification.carrier_turns
        bottom.plot(np.degrees(c), 1 / relative.evaluate(c, 1), "k", label="total i0 (sun : planet)")
        if not isinstance(result.train, IdlerTrain):
            first, second = result.train.stage_ratios(c)
            bottom.plot(np.degrees(c), first, label="stage 1 (sun : intermediate)")
            bottom.plot(np.degrees(c), second, label="stage 2 (intermediate : planet)")
        bottom.set_xlabel("carrier turn c (deg)")
        bottom.set_ylabel("transmission ratio (dimensionless)")
        bottom.legend(fontsize=8, **LEGEND_BESIDE)
    else:
        bottom.set_axis_off()
    return fig


def draw_gears(result: ReverseResult) -> Figure:
    """The pitch curves where they sit on the carrier (mm)."""
    train = result.train
    fig = Figure(figsize=(10, 6), layout="constrained")
    ax = fig.subplots()
    if isinstance(train, IdlerTrain):
        a = train.center_distance
        driver, idler = train.stage_one.points
        ax.plot(*driver.T, label="sun")
        ax.plot(*(idler + [a, 0]).T, label="idler")
        ax.plot(*(train.stage_two.points[1] + [2 * a, 0]).T, label="planet (conjugate of the idler's far side)")
        for center in (0, a, 2 * a):
            ax.plot(center, 0, "k+")
        ax.set_aspect("equal")
        ax.set_xlabel("x along the carrier (mm)")
        ax.set_ylabel("y (mm)")
        ax.legend(fontsize=7, **LEGEND_BESIDE)
    else:
        draw_four_gear_train(ax, train, result.motion.carrier_length)
    ax.set_title(f"pitch curves on the carrier: {result.problem.topology}", fontsize=9)
    return fig


def figure_drawers(result: ReverseResult) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figures by file stem, each drawn when called."""
    require_result(result, ReverseResult, "reverse")
    drawers: dict[str, FigureDrawer] = {"path": partial(draw_path, result), "motion": partial(draw_motion, result)}
    if result.train is not None:
        drawers["gears"] = partial(draw_gears, result)
    if result.tolerance is not None:
        drawers.update(result.tolerance.figure_drawers())
    return drawers


def draw_figures(result: ReverseResult) -> dict[str, Figure]:
    """The figures of a reverse design by file stem: ``path``, ``motion``, ``gears`` when it has a train, and with
    a tolerance analysis ``tolerance_trajectory``, ``tolerance_band`` and ``tolerance_contributions``.

    Parameters
    ----------
    result : ReverseResult
        From ``synthesize``.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
        Save with ``figure.savefig(f"{stem}.png")`` or show in a notebook.
    """
    return drawn(figure_drawers(result))

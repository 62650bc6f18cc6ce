"""Figures of the onion transplanter as matplotlib ``Figure`` objects (no pyplot): the field
trajectory with the planting window, velocity and acceleration of the planting point, and the
Pareto front of the search."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.figure_conventions import LEGEND_BESIDE, FigureDrawer, drawn
from transplanter.parallelogram.kinematics import mechanisms
from transplanter.parallelogram.problem import ParallelogramProblem
from transplanter.parallelogram.result import ParallelogramResult, objective_values
from transplanter.parallelogram.trajectory import measure, sample_path

TURNS = 3


def draw_trajectory(problem: ParallelogramProblem, design: dict, title: str = "") -> Figure:
    """E's path over the field for three plants (mm), the lowest point and the depth window."""
    mech = mechanisms(problem, design)
    path = sample_path(mech, TURNS, 3000)
    m = measure(mech, problem.depth_window, 8192)
    fig = Figure(figsize=(9, 4.8), layout="constrained")
    ax = fig.subplots()
    ax.plot(*path.tip, lw=1.0, label="planting point E")
    for turn in range(TURNS):
        shift = np.array([problem.forward_velocity * turn * problem.period, 0.0])
        window = np.linspace(m.window[0, 0], m.window[1, 0], 200)[None, :] + turn * 2 * np.pi
        segment = mech.state(window)[1][:, 0]
        ax.plot(*segment, color="tab:red", lw=2.5, label="depth window" if turn == 0 else None)
        ax.plot(*(m.lowest[:, 0] + shift), "kv", ms=6, label="planting instant t_E" if turn == 0 else None)
    ax.set_aspect("equal")
    ax.set_xlabel("x / mm (field)")
    ax.set_ylabel("y / mm")
    ax.set_title(title or f"H = {m.depth[0]:.2f} mm, Vx(t_E) = {m.vx_release[0]:.2f} mm/s, "
                 f"Y = {m.vertical_range[0]:.1f} mm, spacing {m.spacing[0]:.1f} mm", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(**LEGEND_BESIDE)
    return fig


def _time_plot(problem, design, pick, ylabel_x: str, ylabel_y: str, unit: str) -> Figure:
    mech = mechanisms(problem, design)
    path = sample_path(mech, 1, 1441)
    m = measure(mech, problem.depth_window, 8192)
    values = pick(path)
    fig = Figure(figsize=(7, 5.5), layout="constrained")
    axes = fig.subplots(2, 1, sharex=True)
    for ax, series, label in zip(axes, values, (ylabel_x, ylabel_y), strict=True):
        ax.plot(path.time, series, lw=1.0)
        ax.axvline(m.planting_time[0], color="tab:red", lw=0.8, ls="--", label="planting instant t_E")
        ax.axhline(0.0, color="k", lw=0.5)
        ax.set_ylabel(f"{label} / {unit}")
        ax.grid(alpha=0.3)
    axes[0].legend(**LEGEND_BESIDE)
    axes[1].set_xlabel(f"time / s (one driver turn, ω1 = {problem.driver_speed:.3f} rad/s)")
    return fig


def draw_velocity(problem: ParallelogramProblem, design: dict) -> Figure:
    """Horizontal and vertical field velocity of E over one turn (mm/s), exact."""
    return _time_plot(problem, design, lambda p: p.velocity, "Vx", "Vy", "mm s⁻¹")


def draw_acceleration(problem: ParallelogramProblem, design: dict) -> Figure:
    """Horizontal and vertical acceleration of E over one turn (mm/s²), exact."""
    return _time_plot(problem, design, lambda p: p.acceleration, "ax", "ay", "mm s⁻²")


def design_figure_drawers(problem: ParallelogramProblem, design: dict) -> dict[str, FigureDrawer]:
    """Trajectory, velocity and acceleration of one design, by file stem, each drawn when called."""
    return {"trajectory": partial(draw_trajectory, problem, design),
            "velocity": partial(draw_velocity, problem, design),
            "acceleration": partial(draw_acceleration, problem, design)}


def draw_design_figures(problem: ParallelogramProblem, design: dict) -> dict[str, Figure]:
    """Trajectory, velocity and acceleration of one design, by file stem."""
    return drawn(design_figure_drawers(problem, design))


def draw_pareto(result) -> Figure:
    """The Pareto front of NSGA-II, objectives pairwise (mm/s, mm), the knee and the picked design marked."""
    f = result.search.objectives
    labels = ("f1 = |Vx(t_E)| / mm s⁻¹", "f2 = |H − H_target| / mm", "f3 = |Y − Y_target| / mm")
    fig = Figure(figsize=(12, 4), layout="constrained")
    axes = fig.subplots(1, 3)
    for ax, (i, j) in zip(axes, ((0, 1), (0, 2), (1, 2)), strict=True):
        ax.scatter(f[:, i], f[:, j], s=14, color="tab:blue", label="Pareto designs")
        ax.scatter(f[0, i], f[0, j], s=90, marker="*", color="tab:red", label="knee (rank 1)")
        ax.set_xscale("symlog", linthresh=1e-3)
        ax.set_yscale("symlog", linthresh=1e-3)
        polished = result.polished
        if polished is not None and polished.variables is not None:
            p = objective_values(result.problem, polished.evaluation)
            ax.scatter(p[i], p[j], s=60, marker="P", color="tab:green", label="NLP polish of it")
        if result.pick != 1:
            k = result.pick - 1
            ax.scatter(f[k, i], f[k, j], s=60, marker="D", facecolor="none", color="k",
                       label=f"picked (rank {result.pick})")
        ax.set_xlabel(labels[i])
        ax.set_ylabel(labels[j])
        ax.grid(alpha=0.3)
    axes[-1].legend(**LEGEND_BESIDE)
    fig.suptitle(f"NSGA-II: population {result.problem.population}, {result.problem.generations} generations, "
                 f"seed {result.problem.seed}: {len(f)} Pareto designs", fontsize=10)
    return fig


def figure_drawers(result: ParallelogramResult) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figures by file stem, each drawn when called."""
    require_result(result, ParallelogramResult, "parallelogram")
    drawers: dict[str, FigureDrawer] = {"pareto": partial(draw_pareto, result),
                                        **design_figure_drawers(result.problem, result.final)}
    if result.tolerance is not None:
        drawers.update(result.tolerance.figure_drawers())
    return drawers


def draw_figures(result: ParallelogramResult) -> dict[str, Figure]:
    """Pareto front, and the final design's (polished, else chosen) trajectory, velocity and acceleration;
    with a tolerance analysis ``tolerance_trajectory``, ``tolerance_band`` and ``tolerance_contributions``."""
    return drawn(figure_drawers(result))

"""Figures of a gear pair as matplotlib ``Figure`` objects: meshing at several angles, ratio and
kinematics, curvature (no pyplot, no backend chosen: a notebook shows them, the command saves them)."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.collections import PolyCollection
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE, FigureDrawer, drawn
from transplanter.gears.composite_teeth import CompositeTeeth
from transplanter.gears.drawings import outlines
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.gears.result import GearResult
from transplanter.geometry.poses import rotate_about


def _filled(ax, outline: np.ndarray, color: str):
    """``outline`` (N, 2) mm filled, as a collection: ``ax.fill`` walks every vertex in Python to update the data
    limits (13 s for the eight outlines of a 100-tooth composite pair)."""
    ax.add_collection(PolyCollection([outline], facecolors=color, edgecolors=color, alpha=0.35, linewidths=0.6))
    ax.autoscale_view()


def draw_mesh(result: GearResult, positions: int = 4) -> Figure:
    """The pair at ``positions`` driver angles: driver turns clockwise, driven counterclockwise (mm)."""
    d = result.design
    shapes = outlines(result)
    fig = Figure(figsize=(4 * positions, 4.4), layout="constrained")
    axes = fig.subplots(1, positions, sharex=True, sharey=True)
    for ax, k in zip(axes, np.linspace(0, len(d.phi1) - 1, positions, endpoint=False).astype(int), strict=True):
        _filled(ax, rotate_about(shapes["driver"], (0.0, 0.0), -d.phi1[k]), "tab:blue")
        _filled(ax, rotate_about(shapes["driven"], (0.0, 0.0), d.phi2[k]) + [d.center_distance, 0], "tab:orange")
        ax.plot([0, d.center_distance], [0, 0], "k+", ms=8)
        ax.plot(d.radius[0][k], 0, "r.", ms=5)
        ax.set_title(f"phi1 = {np.degrees(d.phi1[k]):.0f} deg", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x / mm")
    axes[0].set_ylabel("y / mm")
    fig.suptitle(result.problem.title or result.problem.source, **PROBLEM_TITLE)
    return fig


def draw_kinematics(result: GearResult) -> Figure:
    """Ratio i12, driven speed (rad/s) and acceleration (rad/s^2) against the driver angle (deg)."""
    d = result.design
    phi = np.degrees(d.phi1)
    fig = Figure(figsize=(7, 7), layout="constrained")
    axes = fig.subplots(3, 1, sharex=True)
    axes[0].plot(phi, d.ratio)
    axes[0].set_ylabel("ratio i12 = ω1/ω2")
    axes[1].plot(phi, d.driven_speed)
    axes[1].set_ylabel("ω2 / rad s⁻¹")
    axes[2].plot(phi, d.driven_acceleration)
    axes[2].set_ylabel("α2 / rad s⁻²")
    axes[2].set_xlabel(f"driver angle φ1 / deg (ω1 = {d.driver_speed:.3f} rad/s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    return fig


def draw_curvature(result: GearResult) -> Figure:
    """Curvature radius of each pitch curve (mm, convex parts) against the driver angle (deg)."""
    d = result.design
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.subplots()
    for gear, name in enumerate(("driver", "driven")):
        rho = np.where(d.convexity[gear] > 0, d.curvature_radius[gear], np.nan)
        ax.plot(np.degrees(d.phi1), rho, label=f"{name} (convex parts)")
    if result.problem.module is not None:
        limit = ADDENDUM * result.problem.module / np.sin(result.problem.pressure_angle) ** 2
        cutter = result.teeth.cutter if result.teeth is not None else result.problem.cutter
        reference = "" if cutter == "rack" else "\n(a reference only: these teeth are not rack-cut)"
        ax.axhline(limit, color="r", ls="--", lw=1, label=f"rack undercut limit m/sin²α = {limit:.2f} mm{reference}")
    ax.set_xlabel("driver angle φ1 at the contact point / deg")
    ax.set_ylabel("curvature radius / mm")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    return fig


def figure_drawers(result: GearResult) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figures by file stem, each drawn when called."""
    require_result(result, GearResult, "gears")
    drawers: dict[str, FigureDrawer] = {"gear_mesh": partial(draw_mesh, result),
                                        "gear_kinematics": partial(draw_kinematics, result),
                                        "gear_curvature": partial(draw_curvature, result)}
    if isinstance(result.teeth, CompositeTeeth):
        from transplanter.gears.cusp_figures import draw_cusps

        drawers["gear_cusps"] = partial(draw_cusps, result, result.teeth)
    return drawers


def draw_figures(result: GearResult) -> dict[str, Figure]:
    """The figures of a gear pair by file stem: ``gear_mesh``, ``gear_kinematics``, ``gear_curvature``.

    Parameters
    ----------
    result : GearResult
        From ``synthesize``.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
        With composite teeth also ``gear_cusps`` (each corner zoomed). Save with
        ``figure.savefig(f"{stem}.png")`` or show in a notebook.
    """
    return drawn(figure_drawers(result))

"""Figures of a pick-up mechanism as matplotlib ``Figure`` objects: the tip path with the needle where it
picks and pushes, and the tip speed over a carrier turn."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE, FigureDrawer, drawn
from transplanter.pickup.result import PickupResult


def draw_path(result: PickupResult) -> Figure:
    """Tip path (mm) about the carrier centre, the needle at the picking and pushing points."""
    fig = Figure(figsize=(7, 6), layout="constrained")
    ax = fig.subplots()
    ax.plot(*result.tip.T, color="tab:blue", label="needle tip Q")
    ax.plot(0, 0, "k+", ms=10, label="carrier centre O")
    direction = result.needle_direction()
    for where, colour, name in ((result.problem.picking, "tab:green", "picking"),
                                (result.problem.pushing, "tab:red", "pushing")):
        needle = result.angle_at(where)
        tip = needle.tip
        base = tip - result.problem.arm_length * np.array([np.cos(direction[needle.index]),
                                                           np.sin(direction[needle.index])])
        ax.plot([base[0], tip[0]], [base[1], tip[1]], color=colour, lw=2,
                label=f"{name}: {np.degrees(needle.angle):.1f} deg to the horizontal")
    ax.set_aspect("equal")
    ax.set_xlabel("x / mm")
    ax.set_ylabel("y / mm")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    ax.set_title(result.problem.title or result.problem.source, **PROBLEM_TITLE)
    return fig


def draw_speed(result: PickupResult) -> Figure:
    """Tip speed (mm/s) and the planet's turn against the carrier (deg) over the carrier turn (deg)."""
    fig = Figure(figsize=(8, 5), layout="constrained")
    top, bottom = fig.subplots(2, 1, sharex=True)
    turn = np.degrees(result.carrier_turns)
    top.plot(turn, np.hypot(*result.velocity.T))
    top.set_ylabel("tip speed / mm s⁻¹")
    bottom.plot(turn, np.degrees(result.planet_turn))
    bottom.set_ylabel("planet turn ψ / deg")
    bottom.set_xlabel(f"carrier turn c / deg (ω = {result.problem.speed:.3f} rad/s, counterclockwise)")
    for ax in (top, bottom):
        ax.grid(alpha=0.3)
    return fig


def figure_drawers(result: PickupResult) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figures by file stem, each drawn when called."""
    require_result(result, PickupResult, "pickup")
    return {"pickup_path": partial(draw_path, result), "pickup_speed": partial(draw_speed, result)}


def draw_figures(result: PickupResult) -> dict[str, Figure]:
    """``pickup_path`` and ``pickup_speed`` by file stem."""
    return drawn(figure_drawers(result))

"""The five-bar's loads over the carrier turn as a matplotlib ``Figure`` (no pyplot, no backend chosen): the
carrier's input torque and the train's torque on the rod above, the force in BE and the hinge forces below, the
pushing stroke shaded on both."""
from __future__ import annotations

import textwrap

import numpy as np
from matplotlib.figure import Figure

from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE
from transplanter.fivebar.kinetostatics import Kinetostatics

#: A line style per hinge of ``kinetostatics.HINGES``: forces that coincide (O, A and F without masses) stay visible.
HINGE_STYLES = ("-", (0, (6, 3)), "-.", (0, (2, 2)), (0, (8, 2, 2, 2, 2, 2)))


def _load_text(loads: Kinetostatics) -> str:
    load = loads.load
    applied = (f"constant force ({load.force_n[0]:g}, {load.force_n[1]:g}) N at P" if load.force_n is not None
               else f"{load.resisting_n:g} N at P against its velocity")
    masses = ", ".join(f"{link.replace('_', ' ')} {mass:g}\N{NO-BREAK SPACE}kg"     # the wrap keeps value and unit
                       for link, mass in load.masses_kg.items() if mass > 0)
    return f"{applied} on the pushing stroke; " + (f"weights over the turn: {masses}" if masses else "no link masses")


def draw_load_figure(loads: Kinetostatics, title: str = "") -> Figure:
    """Carrier torque and planet-shaft torque (N m), force in BE (N, tension positive) and the hinge forces' sizes
    (N) against the carrier turn (deg), the pushing stroke shaded; ``title``: the problem's, drawn as written."""
    degrees = np.degrees(loads.turns)
    fig = Figure(figsize=(10, 7), layout="constrained")
    torques, forces = fig.subplots(2, 1, sharex=True)
    stroke = np.degrees(loads.stroke)
    for ax in (torques, forces):
        ax.axvspan(*stroke, color="0.9", label=f"pushing stroke {stroke[0]:g}-{stroke[1]:g} deg")
        ax.axhline(0.0, color="0.5", lw=0.6)
    torques.plot(degrees, loads.carrier_torque, "k-", label="carrier input torque (clockwise +)")
    torques.plot(degrees, loads.planet_torque, "tab:purple", label="train on rod AF about A (counterclockwise +)")
    torques.set_ylabel("torque (N m)")
    forces.plot(degrees, loads.be_force, "k-", lw=1.6, label="force in BE (tension +)")
    for (name, size), style in zip(loads.hinge_magnitudes().items(), HINGE_STYLES, strict=True):
        forces.plot(degrees, size, linestyle=style, lw=1.2, label=f"|hinge force at {name}|")
    forces.plot(degrees, np.hypot(*loads.force_at_p.T), ":", color="tab:gray", label="|planting force at P|")
    forces.set_ylabel("force (N)")
    forces.set_xlabel("carrier turn c, clockwise (deg)")
    forces.set_xlim(0.0, 360.0)
    forces.set_xticks(np.arange(0.0, 361.0, 45.0))
    for ax in (torques, forces):
        ax.legend(fontsize=8, **LEGEND_BESIDE)
    if title:
        fig.suptitle(title, **PROBLEM_TITLE)
    torques.set_title(textwrap.fill(_load_text(loads), 100), fontsize=9, parse_math=False)
    return fig

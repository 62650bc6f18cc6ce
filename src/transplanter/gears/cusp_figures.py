"""The figure of a composite pair zoomed at each driver corner: the corner tooth's incomplete cycloid arches and
the shaper's involute flanks in two colours, the pitch curve, and the driven gear in mesh as the corner passes."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.figure import Figure

from transplanter.figure_conventions import LEGEND_BESIDE
from transplanter.gears.composite_teeth import CompositeTeeth
from transplanter.gears.cycloid_teeth import STRAIGHT_POINTS
from transplanter.gears.pair import driven_angle
from transplanter.gears.result import GearResult
from transplanter.geometry.poses import rotate_about


def draw_cusps(result: GearResult, teeth: CompositeTeeth) -> Figure:
    """One panel per corner of ``teeth`` (the result's), in the pair's frame at the instant the corner is on the
    line of centres (mm)."""
    d = result.design
    module = teeth.plan.pitch / np.pi
    corners = teeth.corner_teeth
    fig = Figure(figsize=(5 * len(corners) + 2, 5), layout="constrained")
    axes = np.atleast_1d(fig.subplots(1, len(corners)))
    for ax, tooth in zip(axes, corners, strict=True):
        phi1 = float(np.interp(tooth.corner_arc, d.arc, d.phi1))
        phi2 = float(driven_angle(d, np.array([phi1]))[0])
        place = partial(rotate_about, pivot=(0.0, 0.0), angle=-phi1)
        driver, pitch = place(teeth.outlines[0]), place(d.points[0])
        driven = rotate_about(teeth.outlines[1], (0.0, 0.0), phi2) + [d.center_distance, 0.0]
        corner = place(d.driver.evaluate(np.array([phi1]))[0][:1, None] * np.array([[np.cos(phi1), np.sin(phi1)]]))[0]
        ax.plot(*driver.T, color="tab:blue", lw=1.2, label="driver: variable involute (shaper)")
        for k, flank in enumerate(tooth.flanks):
            ax.plot(*place(flank[STRAIGHT_POINTS - 1:]).T, color="tab:red", lw=1.8,
                    label="driver: incomplete cycloid arches" if k == 0 else None)
        ax.plot(*driven.T, color="tab:orange", lw=1, label="driven gear (carved by the driver)")
        ax.plot(*pitch.T, "k--", lw=0.6, label="driver pitch curve")
        ax.plot(*corner, "k^", ms=6, label="corner (cusp)")
        half = 3.0 * module
        ax.set_xlim(corner[0] - half, corner[0] + half)
        ax.set_ylim(corner[1] - half, corner[1] + half)
        ax.set_aspect("equal")
        ax.set_xlabel("x / mm")
        ax.set_ylabel("y / mm")
        ax.set_title(f"corner at φ1 = {np.degrees(phi1):.1f} deg; tooth {tooth.thickness_ratio:.3f} pitches thick",
                     fontsize=9)
    axes[-1].legend(fontsize=8, **LEGEND_BESIDE)
    return fig

"""A planetary train drawn: its pitch curves where they sit on the carrier, its meshes' pressure angles."""
from __future__ import annotations

import numpy as np

from transplanter.figure_conventions import LEGEND_BESIDE
from transplanter.geometry.poses import rotate_about
from transplanter.trains.pressure_angle import FLANKS, STAGES


def draw_four_gear_train(ax, train, carrier_length: float, bend_side: float = 1.0):
    """Sun at the pivot, the intermediate shaft at a1 from it, the planet at ``carrier_length``
    on the +x axis; each pair's curves face each other along their line of centers (mm)."""
    a1, a2 = train.center_distances
    shaft_angle = bend_side * np.arccos(np.clip((a1**2 + carrier_length**2 - a2**2) / (2 * a1 * carrier_length), -1, 1))
    shaft = a1 * np.array([np.cos(shaft_angle), np.sin(shaft_angle)])
    planet_center = np.array([carrier_length, 0.0])
    toward_planet = np.arctan2(*(planet_center - shaft)[::-1])
    drawn = ((train.stage_one.points[0], np.zeros(2), shaft_angle, "sun"),
             (train.stage_one.points[1], shaft, shaft_angle, "first intermediate"),
             (train.stage_two.points[0], shaft, toward_planet, "second intermediate"),
             (train.stage_two.points[1], planet_center, toward_planet, "planet"))
    for points, center, angle, label in drawn:
        ax.plot(*(rotate_about(points, (0.0, 0.0), angle) + center).T, label=label)
        ax.plot(*center, "k+")
    ax.plot([0, shaft[0], carrier_length], [0, shaft[1], 0], "k:", lw=0.8)
    ax.set_aspect("equal")
    ax.set_xlabel("x along the carrier (mm)")
    ax.set_ylabel("y (mm)")
    ax.legend(fontsize=7, **LEGEND_BESIDE)


def draw_pressure_angles(ax, pressure):
    """Pressure angle (deg) of both meshes on the drive and coast flank against the carrier turn (deg), with
    the nominal angle, the limit and each stage's largest (``trains.pressure_angle.StagePressureAngles``)."""
    turns = np.degrees(pressure.turns)
    for stage, flanks, colour in zip(STAGES, np.degrees(pressure.flanks), ("C0", "C1"), strict=True):
        for flank, values, style in zip(FLANKS, flanks, ("-", "--"), strict=True):
            ax.plot(turns, values, style, color=colour, lw=1, label=f"{stage}, {flank} flank")
    ax.plot(np.degrees(pressure.largest_turn), np.degrees(pressure.largest), "kv", label="largest of each stage")
    ax.axhline(np.degrees(pressure.nominal), color="gray", ls=":", lw=1,
               label=f"nominal {np.degrees(pressure.nominal):g} deg")
    ax.axhline(np.degrees(pressure.limit), color="r", ls="--", lw=1,
               label=f"limit gears.max_pressure_angle_deg = {np.degrees(pressure.limit):g}")
    ax.set_xlabel("carrier turn c (deg)")
    ax.set_ylabel("gear pressure angle (deg)")
    ax.legend(fontsize=7, **LEGEND_BESIDE)

"""Pitch curves of a planetary train drawn where they sit on the carrier."""
from __future__ import annotations

import numpy as np

from transplanter.figure_conventions import LEGEND_BESIDE
from transplanter.geometry.poses import rotate_about


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

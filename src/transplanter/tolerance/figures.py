"""Figures of a tolerance analysis: the 3-sigma band over the turn with the key poses' error ellipses, and the
dimensions that contribute most (matplotlib ``Figure`` objects, no pyplot)."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure

from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE

if TYPE_CHECKING:
    from transplanter.tolerance.analysis import ToleranceAnalysis

#: Bars in the contribution chart.
BARS = 10


def _ellipse(covariance: np.ndarray, points: int = 90) -> np.ndarray:
    """The 3-sigma ellipse (points, 2) of a 2 x 2 covariance, about the origin."""
    values, vectors = np.linalg.eigh(covariance)
    t = np.linspace(0, 2 * np.pi, points)
    return 3 * (vectors @ (np.sqrt(np.maximum(values, 0))[:, None] * np.array([np.cos(t), np.sin(t)]))).T


def draw_band(analysis: ToleranceAnalysis) -> Figure:
    """The 3-sigma band of the model's point and angle (the five-bar's P and plate angle) over the turn (first
    order and Monte Carlo), and the point's 3-sigma error ellipses at the key poses."""
    model, mc, k = analysis.model, analysis.monte_carlo, analysis.key_count
    whole = model.whole_turn
    fig = Figure(figsize=(10, 7.5), layout="constrained")
    grid = fig.add_gridspec(2, 2 * k)
    position, angle = fig.add_subplot(grid[0, :k]), fig.add_subplot(grid[0, k:])
    turns = model.turns_deg[whole]
    position.plot(turns, analysis.first_order_3sigma_mm[whole], "k-")
    position.plot(turns, mc.position_3sigma_mm[whole], "r--")
    position.plot(turns, analysis.worst_case_mm[whole], ":", color="grey")
    angle.plot(turns, analysis.first_order_3sigma_deg[whole], "k-", label="first order")
    angle.plot(turns, mc.angle_3sigma_deg[whole], "r--", label="Monte Carlo")
    angle.plot(turns, analysis.worst_case_deg[whole], ":", color="grey", label="worst case")
    for ax, unit in ((position, f"{model.point}, 3σ semi-major axis (mm)"), (angle, f"{model.angle}, 3σ (deg)")):
        ax.set_xlabel("input turn (deg)")
        ax.set_ylabel(unit)
        ax.set_ylim(bottom=0)
        for i, turn in enumerate(model.turns_deg[:k]):
            ax.axvline(turn, color="tab:green", lw=0.6, label="key poses" if i == 0 else None)
    angle.legend(fontsize=8, **LEGEND_BESIDE)
    axes = [fig.add_subplot(grid[1, 2 * i:2 * i + 2]) for i in range(k)]
    first = analysis.key_covariance()
    for i, ax in enumerate(axes):
        ax.plot(*_ellipse(first[i]).T, "k-", label="first order")
        ax.plot(*_ellipse(mc.covariance[i]).T, "r--", label="Monte Carlo")
        ax.set_title(model.key_labels[i], fontsize=9, parse_math=False)
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_xlabel("x error (mm)")
        ax.set_ylabel("y error (mm)")
    axes[-1].legend(fontsize=8, **LEGEND_BESIDE)
    fig.suptitle(f"3σ bands of the built mechanism: {model.title}", **PROBLEM_TITLE)
    return fig


def draw_contributions(analysis: ToleranceAnalysis) -> Figure:
    """Each dimension's mean share of the key poses' position and angle variance, the largest ``BARS``."""
    names = np.array(analysis.model.names)
    position, angle = analysis.position_shares.mean(axis=0), analysis.angle_shares.mean(axis=0)
    order = np.argsort(position + angle)[::-1][:BARS][::-1]
    fig = Figure(figsize=(9, 4.5), layout="constrained")
    ax = fig.subplots()
    rows = np.arange(len(order))
    ax.barh(rows - 0.2, 100 * position[order], 0.4, label=f"{analysis.model.point} position")
    ax.barh(rows + 0.2, 100 * angle[order], 0.4, label=analysis.model.angle)
    ax.set_yticks(rows, names[order], fontsize=8)
    ax.set_xlabel("mean share of the key poses' variance (%)")
    ax.set_ylabel("dimension")
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    fig.suptitle(analysis.model.title, **PROBLEM_TITLE)
    return fig


def draw_figures(analysis: ToleranceAnalysis) -> dict[str, Figure]:
    """``tolerance_band`` and ``tolerance_contributions``."""
    return {"tolerance_band": draw_band(analysis), "tolerance_contributions": draw_contributions(analysis)}

"""Figures of a tolerance analysis: the trajectory with its 3-sigma band and the key poses' error ellipses (x-y),
the 3-sigma band over the turn with the ellipses about the key poses, and the dimensions that contribute most
(matplotlib ``Figure`` objects, no pyplot)."""
from __future__ import annotations

from functools import partial
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure

from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE, FigureDrawer
from transplanter.tolerance.bands import position_covariance

if TYPE_CHECKING:
    from transplanter.tolerance.analysis import ToleranceAnalysis

#: Bars in the contribution chart.
BARS = 10
#: The trajectory figure magnifies the band so the widest is drawn up to this fraction of the path's extent.
DRAWN_BAND = 0.05


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


def band_normal_offsets(path: np.ndarray, covariance: np.ndarray, closed: bool) -> tuple[np.ndarray, np.ndarray]:
    """Unit normals (T, 2) of a path (T, 2) sampled along the turn, and the 3-sigma extent (T,) of its error
    ellipses (covariances (T, 2, 2)) along them: 3 sqrt(n^T C n), the band's half-width where the path runs.
    The tangent is the central difference of the samples (periodic on a ``closed`` path, one-sided at the ends
    of an open one)."""
    tangent = (np.roll(path, -1, axis=0) - np.roll(path, 1, axis=0)) if closed else np.gradient(path, axis=0)
    normal = np.c_[-tangent[:, 1], tangent[:, 0]] / np.linalg.norm(tangent, axis=1)[:, None]
    return normal, 3 * np.sqrt(np.maximum(np.einsum("ti,tij,tj->t", normal, covariance, normal), 0))


def magnification(band_mm: float, extent_mm: float) -> float:
    """The 1-2-5 factor that draws the largest band at most ``DRAWN_BAND`` of the path's extent, at least 1."""
    wanted = DRAWN_BAND * extent_mm / band_mm if band_mm > 0 else 1.0
    if wanted <= 1:
        return 1.0
    decade = 10 ** np.floor(np.log10(wanted))
    return float(max(f * decade for f in (1, 2, 5) if f * decade <= wanted))


def draw_trajectory_band(analysis: ToleranceAnalysis) -> Figure:
    """The model's point along the whole turn (x-y, mm) with its 3-sigma band, the path offset either side by the
    3-sigma error ellipse's extent along the path's normal (first order and Monte Carlo), and the key poses'
    3-sigma error ellipses; band and ellipses magnified by one stated factor so they show beside the path."""
    model, mc, k = analysis.model, analysis.monte_carlo, analysis.key_count
    whole = model.whole_turn
    motion = model.sampled(model.nominal[None])[0]
    path = motion[:2, whole].T
    steps = np.linalg.norm(np.diff(path, axis=0), axis=1)
    closed = bool(np.linalg.norm(path[0] - path[-1]) <= 2 * np.median(steps))
    first = position_covariance(analysis.jacobian[:2], analysis.sigma)
    extent = float(np.ptp(path, axis=0).max())
    factor = magnification(float(max(analysis.first_order_3sigma_mm[whole].max(), mc.position_3sigma_mm[whole].max())),
                            extent)
    fig = Figure(figsize=(9, 7), layout="constrained")
    ax = fig.subplots()
    ends = (lambda xy: np.vstack([xy, xy[:1]])) if closed else (lambda xy: xy)
    ax.plot(*ends(path).T, "k-", lw=0.8, label=f"designed {model.point}")
    for covariance, style, name in ((first[whole], "-", "first order"), (mc.covariance[whole], "--", "Monte Carlo")):
        normal, width = band_normal_offsets(path, covariance, closed)
        for side in (1, -1):
            ax.plot(*ends(path + side * factor * width[:, None] * normal).T, style, lw=0.8,
                    color="tab:blue" if style == "-" else "tab:red", label=f"3σ band, {name}" if side == 1 else None)
    for i in range(k):
        centre = motion[:2, i]
        ax.plot(*(centre + factor * _ellipse(first[i])).T, "-", color="tab:green", lw=1.2,
                label="3σ ellipse at the key poses, first order" if i == 0 else None)
        ax.plot(*(centre + factor * _ellipse(mc.covariance[i])).T, ":", color="tab:olive", lw=1.2,
                label="3σ ellipse at the key poses, Monte Carlo" if i == 0 else None)
        ax.annotate(model.key_labels[i], centre, textcoords="offset points", xytext=(6, 6), fontsize=8)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"the built mechanism's {model.point}: 3σ band and error ellipses, drawn {factor:g}× their size",
                 fontsize=9, parse_math=False)
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    fig.suptitle(model.title, **PROBLEM_TITLE)
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


def figure_drawers(analysis: ToleranceAnalysis) -> dict[str, FigureDrawer]:
    """``tolerance_trajectory``, ``tolerance_band`` and ``tolerance_contributions``, each drawn when called."""
    return {"tolerance_trajectory": partial(draw_trajectory_band, analysis),
            "tolerance_band": partial(draw_band, analysis),
            "tolerance_contributions": partial(draw_contributions, analysis)}

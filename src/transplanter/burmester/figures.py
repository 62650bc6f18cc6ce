"""The figure of a dyad synthesis as a matplotlib ``Figure`` (no pyplot, no backend chosen:
a notebook shows it, the command saves it)."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.burmester.result import Synthesis
from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE, FigureDrawer, drawn
from transplanter.geometry.curve_trace import CurveTrace

#: How many dyads of a 4-pose family are drawn as links (all of them would hide the curves).
FAMILY_LINKS = 12


def _curve(ax, curve: CurveTrace | None, color: str, label: str):
    if curve is None:
        return
    for k, run in enumerate(curve.runs):
        ax.plot(*curve.points[run].T, color=color, lw=1.2, label=label if k == 0 else None)


def _poses(ax, poses: np.ndarray, labels, size: float):
    """Each pose as a bar along the body's direction from its reference point (dot)."""
    for k, (x, y, angle) in enumerate(poses):
        tip = np.array([x, y]) + size * np.array([np.cos(angle), np.sin(angle)])
        ax.annotate("", xy=tip, xytext=(x, y),
                    arrowprops={"arrowstyle": "-|>", "color": "k", "lw": 1.2, "mutation_scale": 9})
        ax.plot(x, y, "ko", ms=3)
        ax.annotate(labels[k] if labels else f"P{k + 1}", (x, y), textcoords="offset points", xytext=(4, -10),
                    fontsize=8, parse_math=False)
    ax.plot([], [], "k-", lw=1.2, label="poses (reference point, direction)")


def draw_synthesis(result: Synthesis) -> Figure:
    """Poses as oriented arrows, the Burmester curves, and the dyads (links) in pose 1 (mm)."""
    problem = result.problem
    fig = Figure(figsize=(9.5, 7), layout="constrained")
    ax = fig.subplots()
    _curve(ax, result.center_curve, "tab:blue", "center-point curve")
    _curve(ax, result.circle_curve, "tab:orange", "circle-point curve")
    dyads = result.dyads
    if result.center_curve is not None and len(dyads) > FAMILY_LINKS:
        dyads = [dyads[k] for k in np.linspace(0, len(dyads) - 1, FAMILY_LINKS).astype(int)]
    for k, d in enumerate(dyads):
        ax.plot(*np.array([d.center, d.circle]).T, color="tab:green", lw=1, alpha=0.8,
                label="dyads in pose 1" if k == 0 else None)
        ax.plot(*d.center, "^", color="tab:blue", ms=7)
        ax.plot(*d.circle, "o", color="tab:orange", ms=5)
    if len(problem.poses) == 5 and result.dyads:
        ax.plot([], [], "^", color="tab:blue", label="Burmester center points")
        ax.plot([], [], "o", color="tab:orange", label="Burmester circle points")
    if problem.link is not None:
        ax.plot(*problem.link.pivot, "ks", ms=8, label="link pivot")
    scale = result.dyads[0].scale if result.dyads else 1.0
    _poses(ax, problem.poses, problem.labels, 0.6 * scale)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x / mm")
    ax.set_ylabel("y / mm")
    ax.set_title(problem.title or problem.source, **PROBLEM_TITLE)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    return fig


def figure_drawers(result: Synthesis) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figure by file stem, drawn when called."""
    require_result(result, Synthesis, "burmester")
    return {"burmester": partial(draw_synthesis, result)}


def draw_figures(result: Synthesis) -> dict[str, Figure]:
    """The figures of a synthesis by file stem: ``{"burmester": Figure}``.

    Parameters
    ----------
    result : Synthesis
        From ``synthesize``.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
        Save with ``figure.savefig(f"{stem}.png")`` or show in a notebook.
    """
    return drawn(figure_drawers(result))

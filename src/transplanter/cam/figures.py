"""Figures of a cam as matplotlib ``Figure`` objects (no pyplot, no backend chosen): the s-v-a-j
diagrams, the pressure angle, and the profile with the follower drawn at several cam angles."""
from __future__ import annotations

from functools import partial

import numpy as np
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.cam.kinematics import segment_starts
from transplanter.cam.result import CamResult
from transplanter.figure_conventions import LEGEND_BESIDE, FigureDrawer, drawn
from transplanter.geometry.poses import rotate_about


def _segment_lines(ax, result: CamResult):
    for start in np.degrees(segment_starts(result.problem.segments)[1:-1]):
        ax.axvline(start, color="0.6", lw=0.6, ls=":")


def draw_motion(result: CamResult) -> Figure:
    """Displacement, velocity, acceleration and jerk of the follower against the cam angle (deg)."""
    g = result.geometry
    swing = result.problem.oscillating
    unit, scale = ("deg", np.degrees(1.0)) if swing else ("mm", 1.0)
    fig = Figure(figsize=(8, 8), layout="constrained")
    axes = fig.subplots(4, 1, sharex=True)
    labels = (f"s / {unit}", f"ds/dθ / {unit} rad⁻¹", f"d²s/dθ² / {unit} rad⁻²", f"d³s/dθ³ / {unit} rad⁻³")
    angle = np.degrees(g.angle)
    for ax, values, label in zip(axes, g.motion, labels, strict=True):
        ax.plot(angle, values * scale, lw=1)
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
        _segment_lines(ax, result)
    for jump in result.checks.acceleration_jumps:
        axes[2].plot(np.degrees(jump.angle), 0, "rv", ms=6)
    axes[-1].set_xlabel("cam angle θ / deg (dotted: segment ends; red marks: acceleration jumps)")
    laws = ", ".join(f"{s.kind} {s.law}" for s in result.problem.segments if s.law)
    fig.suptitle(f"follower motion: {laws}", fontsize=9)
    return fig


def draw_pressure_angle(result: CamResult) -> Figure:
    """Pressure angle (deg) against the cam angle (deg), with the limit and the largest on rise and return."""
    g, checks = result.geometry, result.checks
    fig = Figure(figsize=(9, 4), layout="constrained")
    ax = fig.subplots()
    ax.plot(np.degrees(g.angle), np.degrees(g.pressure_angle), lw=1, label="pressure angle")
    limit = np.degrees(result.problem.pressure_limit)
    ax.axhline(limit, color="r", ls="--", lw=1, label=f"limit ±{limit:g} deg")
    ax.axhline(-limit, color="r", ls="--", lw=1)
    for kind, marker in (("rise", "^"), ("return", "v")):
        extreme = checks.pressure[kind]
        if extreme is not None:
            k = int(np.argmin(np.abs(g.angle - extreme.angle)))
            value = np.copysign(np.degrees(extreme.value), g.pressure_angle[k])
            ax.plot(np.degrees(extreme.angle), value, "k" + marker, label=f"largest on {kind}: {abs(value):.2f} deg")
    _segment_lines(ax, result)
    ax.set_xlabel("cam angle θ / deg")
    ax.set_ylabel("pressure angle / deg")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    return fig


def _draw_follower(ax, result: CamResult, k: int):
    """The follower at sample ``k`` on the ground: roller and arm or stem, or the flat face and its stem."""
    g, follower = result.geometry, result.problem.follower
    center, style = g.center[k], {"color": "tab:orange", "lw": 2}
    if follower.kind == "flat_faced":                 # the face across the contact point, and the stem
        ax.plot([g.center[:, 0].min() - 2, g.center[:, 0].max() + 2], [center[1], center[1]], **style)
        ax.plot([0, 0], [center[1], g.center[:, 1].max() + 10], **style)
        return
    circle = np.linspace(0, 2 * np.pi, 73)
    ax.plot(center[0] + follower.roller_radius * np.cos(circle), center[1] + follower.roller_radius * np.sin(circle),
            color="tab:orange", lw=1.2)
    if follower.kind == "oscillating":
        pivot, _ = follower.arm
        ax.plot(*np.array([pivot, center]).T, **style)
        ax.plot(*pivot, "k^", ms=7)
    else:
        ax.plot([center[0], center[0]], [center[1], np.abs(g.center[:, 1]).max() + follower.roller_radius], **style)


def draw_profile(result: CamResult, positions: int = 4) -> Figure:
    """The cam turned to ``positions`` cam angles on the ground, with the roller and the follower (mm)."""
    g, problem = result.geometry, result.problem
    follower = problem.follower
    fig = Figure(figsize=(4 * positions, 4.6), layout="constrained")
    axes = fig.subplots(1, positions, sharex=True, sharey=True)
    for ax, k in zip(axes, np.linspace(0, g.angle.size, positions, endpoint=False).astype(int), strict=True):
        turn = problem.direction * g.angle[k]
        ax.fill(*rotate_about(g.profile, (0.0, 0.0), turn).T, color="tab:blue", alpha=0.3, lw=0.8, ec="tab:blue")
        if follower.kind != "flat_faced":
            ax.plot(*rotate_about(g.pitch, (0.0, 0.0), turn).T, color="tab:blue", lw=0.6, ls="--")
        _draw_follower(ax, result, k)
        ax.plot(0, 0, "k+", ms=9)
        ax.set_title(f"θ = {np.degrees(g.angle[k]):.0f} deg", fontsize=9)
        ax.set_aspect("equal")
        ax.set_xlabel("x / mm")
    axes[0].set_ylabel("y / mm")
    sense = "counterclockwise" if problem.direction > 0 else "clockwise"
    fig.suptitle(f"cam turning {sense}, base radius {result.base_radius:.3f} mm; dashed: pitch curve", fontsize=10)
    return fig


def figure_drawers(result: CamResult) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figures by file stem, each drawn when called."""
    require_result(result, CamResult, "cam")
    return {"cam_motion": partial(draw_motion, result), "cam_pressure_angle": partial(draw_pressure_angle, result),
            "cam_profile": partial(draw_profile, result)}


def draw_figures(result: CamResult) -> dict[str, Figure]:
    """The figures of a cam by file stem: ``cam_motion``, ``cam_pressure_angle``, ``cam_profile``.

    Parameters
    ----------
    result : CamResult
        From ``synthesize``.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
    """
    return drawn(figure_drawers(result))

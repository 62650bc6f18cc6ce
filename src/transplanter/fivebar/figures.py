"""Figures of a five-bar design: solution region (Wang et al. 2025 Figure 5), relative angle (Figure 9),
gear train (Figure 10), trajectory with the plate at the key poses (Figure 15b) and the trade-off
of the alternatives, as matplotlib ``Figure`` objects (no pyplot, no backend chosen: a notebook
shows them, the command saves them)."""
from __future__ import annotations

import textwrap
from functools import partial

import numpy as np
from matplotlib.figure import Figure
from matplotlib.layout_engine import ConstrainedLayoutEngine

from transplanter.api_arguments import require_result
from transplanter.cam.figures import figure_drawers as cam_figure_drawers
from transplanter.figure_conventions import LEGEND_BESIDE, PROBLEM_TITLE, FigureDrawer, drawn
from transplanter.fivebar.gears_on_carrier import gears_on_carrier, tooth_outlines
from transplanter.fivebar.load_figures import draw_load_figure
from transplanter.fivebar.result import FiveBarResult
from transplanter.fivebar.support import SupportDesign
from transplanter.trains.figures import draw_pressure_angles


def draw_region(result: FiveBarResult) -> Figure:
    """Hinge solution curves (mm), those within the ranges, the feasible five-bars and the design."""
    fig = Figure(figsize=(10, 7.5), layout="constrained")
    ax = fig.subplots()
    for family, names, colors in ((result.region.receiving, ("B", "E"), ("tab:blue", "tab:cyan")),
                                  (result.region.carrier, ("A", "F"), ("tab:red", "tab:orange"))):
        for points, name, color in ((family.fixed, names[0], colors[0]), (family.moving, names[1], colors[1])):
            ax.plot(*points.T, ".", ms=1.2, color=color, alpha=0.35)
            ax.plot(*points[family.kept].T, ".", ms=5, color=color, label=f"{name}: within ranges (bold)")
    feasible = result.region.feasible
    if feasible:
        hinges = np.array([[c.mech.hinge_b, c.mech.carrier_point(0.0)] for c in feasible])
        ax.plot(*hinges[:, 0].T, "s", mfc="none", color="k", ms=7, label="feasible five-bars (B, A)")
        ax.plot(*hinges[:, 1].T, "s", mfc="none", color="k", ms=7)
    mech = result.design.mech
    e, f = mech.plate_points(result.problem.poses[0])
    for point, name in ((mech.hinge_b, "B"), (mech.carrier_point(0.0), "A"), (e, "E"), (f, "F")):
        ax.plot(*point, "k*", ms=11)
        ax.annotate(f" {name}", (float(point[0]), float(point[1])))
    ax.plot(*result.problem.poses[:, :2].T, "k^", ms=6, label="key poses P1-P4")
    ax.set_aspect("equal")
    ax.set_title("Hinge solution curves; bold: within Table 2 ranges and free of chain defects\n"
                 "stars: refined design in pose 1", fontsize=9)
    ax.legend(fontsize=7, **LEGEND_BESIDE)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_xlim(-250, 150)
    ax.set_ylim(-400, 100)
    return fig


def draw_relative_angle(result: FiveBarResult) -> Figure:
    """Relative angle of rod I (deg) and total ratio i0 against the carrier turn (deg)."""
    relative, stroke = result.design.relative_angle, result.design.stroke
    grid = result.verification.carrier_turns
    fig = Figure(figsize=(10, 4.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(np.degrees(grid), np.degrees(relative.evaluate(grid) - relative.rho1), "k-", label="rho - rho1 (B-spline)")
    key = result.problem.carrier_turns
    ax.plot(np.degrees(key), np.degrees(relative.evaluate(key) - relative.rho1), "ro", label="key poses P1-P4")
    ax.plot(np.degrees(stroke.carrier_turns), np.degrees(stroke.relative_angles - relative.rho1), "bs",
            label="return points P5-P9")
    ax.set_xlabel("carrier turn c, clockwise (deg)")
    ax.set_ylabel("rod I relative to carrier (deg)")
    twin = ax.twinx()
    twin.plot(np.degrees(grid), 1 / relative.evaluate(grid, 1), "g--", lw=1, label="total ratio i0 = dc/drho")
    twin.set_ylabel("total ratio i0 (dimensionless)", color="g")
    lines = ax.get_lines() + twin.get_lines()
    fig.legend(lines, [str(line.get_label()) for line in lines], fontsize=8, loc="outside right upper")
    return fig


def draw_gears(result: FiveBarResult) -> Figure:
    """Stage ratios against the carrier turn (deg), and the four cut gears on the carrier at
    pose 1 (mm)."""
    train = result.train
    grid = result.verification.carrier_turns
    first, second = train.stage_ratios(grid)
    fig = Figure(figsize=(14, 5), layout="constrained")
    ax, right = fig.subplots(1, 2)
    for values, label in ((first * second, "i0 (total)"), (first, "I1 corrected (sun : intermediate)"),
                          (second, "I2 corrected (intermediate : planet)")):
        ax.plot(np.degrees(grid), values, label=label)
    ax.set_xlabel("carrier turn c (deg)")
    ax.set_ylabel("transmission ratio (dimensionless)")
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    outlines = tooth_outlines(result.toothed)
    for gear, teeth in zip(gears_on_carrier(train, float(result.design.mech.carrier_length)),
                           np.repeat(result.toothed.counts, 2), strict=True):
        line, = right.plot(*gear.placed(outlines[gear.name], 0.0)[0].T, lw=0.7,
                           label=f"{gear.name.replace('_', ' ')} ({gear.role}), {teeth} teeth")
        right.plot(*gear.center, "k+")
    right.set_aspect("equal")
    right.set_xlabel("x along the carrier O-A (mm)")
    right.set_ylabel("y on the carrier (mm)")
    right.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.12), ncols=2)
    right.set_title("the cut gears on the carrier (O at the origin, A on +x) at pose 1\n(pitch curves: each gear's "
                    "DXF, layer PITCH, and CSV)", fontsize=9)
    return fig


def draw_trajectory(result: FiveBarResult) -> Figure:
    """P over a turn from the forward simulation, the plate at the key poses, the linkage in pose 1 (mm)."""
    problem, mech, check = result.problem, result.design.mech, result.verification
    fig = Figure(figsize=(9.5, 7), layout="constrained")
    ax = fig.subplots()
    ax.plot(*check.trajectory.T, "k-", lw=1, label="P over a turn (gears rolling, then linkage)")
    e, f = mech.plate_points(problem.poses)
    for k, pose in enumerate(problem.poses):
        ax.fill(*np.array([e[k], f[k], pose[:2]]).T, color="tab:green", alpha=0.4, ec="tab:green")
        ax.annotate(f" {problem.labels[k]}", pose[:2], fontsize=8, parse_math=False)
    ax.plot(*problem.return_points.T, "bx", label="return points")
    a = mech.carrier_point(0.0)
    ax.plot(*np.array([[0, 0], a, f[0]]).T, "r-o", ms=3, label="O-A-F (pose 1)")
    ax.plot(*np.array([mech.hinge_b, e[0]]).T, "b-o", ms=3, label="B-E (pose 1)")
    for point, name in ((np.zeros(2), "O"), (a, "A"), (mech.hinge_b, "B"), (e[0], "E"), (f[0], "F"),
                        (problem.poses[0, :2], "P")):
        ax.annotate(name, (float(point[0]), float(point[1])), xytext=(4, 4), textcoords="offset points", fontsize=10,
                    fontweight="bold")
    ax.set_aspect("equal")
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    return fig


def draw_tradeoff(result: FiveBarResult) -> Figure:
    """Largest return-point miss (mm) against the smallest transmission angle at E (deg) of each refined alternative,
    labelled with its rank, the picked one ringed, the return tolerance drawn; the bounds the picked one
    sits on are listed under the axes."""
    alternatives = result.alternatives
    angles = np.degrees([a.transmission_angle for a in alternatives])
    misses = np.array([a.largest_miss_mm for a in alternatives])
    tolerance = result.problem.return_tolerance_mm
    fig = Figure(figsize=(8, 5.5), layout="constrained")
    ax = fig.subplots()
    ax.plot(angles, misses, "o", color="tab:blue", label="refined alternatives (rank)")
    for rank, (angle, miss) in enumerate(zip(angles, misses, strict=True), start=1):
        ax.annotate(str(rank), (angle, miss), xytext=(5, 5), textcoords="offset points", fontsize=9)
    picked = result.picked - 1
    ax.plot(angles[picked], misses[picked], "o", mfc="none", mec="tab:red", ms=14, mew=2,
            label=f"picked: alternative {result.picked}")
    ax.axhline(tolerance, color="gray", ls="--", lw=1, label=f"return tolerance {tolerance:g} mm")
    ax.set_ylim(0, 1.2 * max(tolerance, misses.max()) or 1.0)
    ax.ticklabel_format(useOffset=False)
    ax.set_xlabel("smallest transmission angle at E over the turn (deg)")
    ax.set_ylabel("largest return-point miss (mm)")
    starts = sum(len(a.starts) for a in alternatives)
    count, failed = len(alternatives), len(result.failed)
    ax.set_title(f"{count} distinct design{'s' if count > 1 else ''} refined from {starts} of {starts + failed} "
                 f"region candidates" + (f" ({failed} failed: see the report)" if failed else ""), fontsize=9)
    bounds = ", ".join(map(str, result.chosen.active_bounds)) or "no bound"
    fig.text(0.01, 0.0, textwrap.fill(f"The picked design sits on: {bounds}", 110), fontsize=8, va="bottom",
             parse_math=False)
    engine = fig.get_layout_engine()
    assert isinstance(engine, ConstrainedLayoutEngine)      # the figure is made with layout="constrained"
    engine.set(rect=(0, 0.08, 1, 0.92))
    ax.legend(fontsize=8, **LEGEND_BESIDE)
    return fig


def draw_support(support: SupportDesign) -> Figure:
    """Left: the seedling support at pose 1 (plate low) and at its highest, the cam at pose 1, hinge E's path and the
    plate line (mm). Right: the plate height and its clearance left of E against the carrier turn, stages shaded."""
    fig = Figure(figsize=(14, 6), layout="constrained")
    ground, timing = fig.subplots(1, 2)
    turns = support.carrier_turns
    high = turns[int(np.nanargmax(support.plate_height))]
    for turn, style, when in ((0.0, "-", "pose 1"), (high, "--", f"highest, carrier turn {np.degrees(high):.0f} deg")):
        joints = {name: points[0] for name, points in support.joints([turn]).items()}
        ground.plot(*np.array([joints[n] for n in "CGHZ"]).T, "m" + style + "o", ms=3, label=f"C-G-H-Z ({when})")
        ground.plot(*np.array([joints["C"], joints["K"]]).T, "c" + style + "o", ms=3, label=f"arm C-K ({when})")
        ground.plot(*support.cam_outline(turn).T, "k" + style, lw=1, label=f"cam profile ({when})")
    ground.plot(*support.cam_outline(0.0, "pitch").T, "k:", lw=0.8, label="pitch curve")
    ground.plot(*support.hinge_e.T, "b-", lw=1, label="hinge E over a turn")
    x_z = support.spec.linkage.plate_x
    ground.axvline(x_z, color="m", lw=0.8, ls=":", label=f"plate line x_Z = {x_z:g}")
    least = support.hinge_e[np.argmin(support.hinge_e[:, 0])]
    ground.annotate(f"clearance {support.clearance_mm:.1f} mm", least, xytext=(8, -12), textcoords="offset points",
                    fontsize=8)
    for name in "CD":
        point = support.joints([0.0])[name][0]
        ground.annotate(name, point, xytext=(4, 4), textcoords="offset points", fontweight="bold")
    ground.set(aspect="equal", xlabel="x (mm)", ylabel="y (mm)", title="seedling support (ground frame)")
    ground.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.1), ncols=3)
    degrees = np.degrees(turns)
    timing.plot(degrees, support.plate_height, "m-", label="plate height y_Z")
    edges = np.degrees(np.cumsum(np.r_[0.0, support.stages]))
    for (start, end), name, shade in zip(zip(edges[:-1], edges[1:], strict=True), ("push", "receive", "return", "rest"),
                                         ("0.85", "0.95", "0.85", "0.95"), strict=True):
        timing.axvspan(start, end, color=shade)
        timing.text((start + end) / 2, 1.0, name, transform=timing.get_xaxis_transform(), ha="center", va="bottom",
                     fontsize=8)
    timing.set(xlabel="carrier turn, clockwise from pose 1 (deg)", ylabel="y_Z (mm)")
    gap = timing.twinx()
    gap.plot(degrees, support.hinge_e[:, 0] - x_z, "b--", lw=1, label="x_E - x_Z")
    gap.axhline(0.0, color="r", lw=0.8)
    gap.set_ylabel("clearance left of hinge E (mm)", color="b")
    lines = timing.get_lines() + gap.get_lines()[:1]
    timing.legend(lines, [line.get_label() for line in lines], fontsize=8, loc="upper center",
                  bbox_to_anchor=(0.5, -0.12), ncols=2)
    return fig


def draw_pressure_angle(result: FiveBarResult) -> Figure:
    """The gear pressure angle of both meshes, drive and coast flank, over the carrier turn."""
    fig = Figure(figsize=(9, 4.5), layout="constrained")
    draw_pressure_angles(fig.subplots(), result.pressure)
    if result.problem.title:
        fig.suptitle(result.problem.title, **PROBLEM_TITLE)
    return fig


def figure_drawers(result: FiveBarResult) -> dict[str, FigureDrawer]:
    """``draw_figures``'s figures by file stem, each drawn when called."""
    require_result(result, FiveBarResult, "fivebar")
    drawers: dict[str, FigureDrawer] = {
        "region": partial(draw_region, result), "relative_angle": partial(draw_relative_angle, result),
        "gears": partial(draw_gears, result), "trajectory": partial(draw_trajectory, result),
        "tradeoff": partial(draw_tradeoff, result),
        "loads": partial(draw_load_figure, result.loads, result.problem.title),
        "pressure_angle": partial(draw_pressure_angle, result)}
    if result.support is not None:
        drawers["support"] = partial(draw_support, result.support)
        drawers.update(cam_figure_drawers(result.support.cam))
    if result.tolerance is not None:
        drawers.update(result.tolerance.figure_drawers())
    return drawers


def draw_figures(result: FiveBarResult) -> dict[str, Figure]:
    """The figures of a five-bar design by file stem: ``region``, ``relative_angle``, ``gears``, ``trajectory``,
    ``tradeoff``, ``loads``, ``pressure_angle``, with a seedling support ``support`` and the cam's own
    (``cam_motion``, ...), and with a tolerance analysis ``tolerance_trajectory``, ``tolerance_band`` and
    ``tolerance_contributions``.

    Parameters
    ----------
    result : FiveBarResult
        From ``synthesize``.

    Returns
    -------
    dict of str to matplotlib.figure.Figure
        Save with ``figure.savefig(f"{stem}.png")`` or show in a notebook.
    """
    return drawn(figure_drawers(result))

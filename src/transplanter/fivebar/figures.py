"""Figures of a five-bar design: solution region (seed 000 Figure 5), relative angle (Figure 9),
gear train (Figure 10) and trajectory with the plate at the key poses (Figure 15b)."""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from transplanter.fivebar.synthesis import FiveBarResult  # noqa: E402
from transplanter.trains.figures import draw_four_gear_train  # noqa: E402


def plot_region(result: FiveBarResult, path: str):
    fig, ax = plt.subplots(figsize=(7.5, 7.5))
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
        ax.annotate(f" {name}", point)
    ax.plot(*result.problem.poses[:, :2].T, "k^", ms=6, label="key poses P1-P4")
    ax.set_aspect("equal")
    ax.set_title("Hinge solution curves; bold: within Table 2 ranges and free of chain defects\n"
                 "stars: refined design in pose 1", fontsize=9)
    ax.legend(fontsize=7, loc="best")
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_xlim(-250, 150)
    ax.set_ylim(-400, 100)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_relative_angle(result: FiveBarResult, path: str):
    relative, stroke = result.design.relative_angle, result.design.stroke
    grid = result.verification.carrier_turns
    fig, ax = plt.subplots(figsize=(8, 4.5))
    ax.plot(np.degrees(grid), np.degrees(relative.evaluate(grid) - relative.rho1), "k-", label="rho - rho1 (B-spline)")
    key = result.problem.carrier_turns
    ax.plot(np.degrees(key), np.degrees(relative.evaluate(key) - relative.rho1), "ro", label="key poses P1-P4")
    ax.plot(np.degrees(stroke.carrier_turns), np.degrees(stroke.relative_angles - relative.rho1), "bs",
            label="return points P5-P9")
    ax.set_xlabel("carrier turn c, clockwise (deg)")
    ax.set_ylabel("rod I relative to carrier (deg)")
    twin = ax.twinx()
    twin.plot(np.degrees(grid), 1 / relative.evaluate(grid, 1), "g--", lw=1, label="total ratio i0 = dc/drho")
    twin.set_ylabel("i0", color="g")
    ax.legend(loc="upper left", fontsize=8)
    twin.legend(loc="lower right", fontsize=8)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_gears(result: FiveBarResult, path: str):
    train = result.train
    grid = result.verification.carrier_turns
    first, second = train.stage_ratios(grid)
    fig, (ax, right) = plt.subplots(1, 2, figsize=(12, 5))
    for values, label in ((first * second, "i0 (total)"), (first, "I1 corrected (sun : intermediate)"),
                          (second, "I2 corrected (intermediate : planet)")):
        ax.plot(np.degrees(grid), values, label=label)
    ax.set_xlabel("carrier turn c (deg)")
    ax.set_ylabel("transmission ratio")
    ax.legend(fontsize=8)
    draw_four_gear_train(right, train, result.design.mech.carrier_length)
    right.set_title("pitch curves on the carrier (O left, A right) at pose 1", fontsize=9)
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_trajectory(result: FiveBarResult, path: str):
    problem, mech, check = result.problem, result.design.mech, result.verification
    fig, ax = plt.subplots(figsize=(7, 7))
    ax.plot(*check.trajectory.T, "k-", lw=1, label="P over a turn (gears rolling, then linkage)")
    e, f = mech.plate_points(problem.poses)
    for k, pose in enumerate(problem.poses):
        ax.fill(*np.array([e[k], f[k], pose[:2]]).T, color="tab:green", alpha=0.4, ec="tab:green")
        ax.annotate(f" {problem.labels[k]}", pose[:2], fontsize=8)
    ax.plot(*problem.return_points.T, "bx", label="return points")
    a = mech.carrier_point(0.0)
    ax.plot(*np.array([[0, 0], a, f[0]]).T, "r-o", ms=3, label="O-A-F (pose 1)")
    ax.plot(*np.array([mech.hinge_b, e[0]]).T, "b-o", ms=3, label="B-E (pose 1)")
    ax.set_aspect("equal")
    ax.legend(fontsize=8)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    fig.savefig(path, dpi=120, bbox_inches="tight")
    plt.close(fig)


def plot_fivebar_figures(result: FiveBarResult, out: Path) -> list[str]:
    out.mkdir(parents=True, exist_ok=True)
    figures = {"region.png": plot_region, "relative_angle.png": plot_relative_angle, "gears.png": plot_gears,
               "trajectory.png": plot_trajectory}
    for name, plot in figures.items():
        plot(result, str(out / name))
    return list(figures)

"""Figures of a gear pair: meshing at several angles, ratio and kinematics, curvature."""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from transplanter.gears.drawings import outlines  # noqa: E402
from transplanter.gears.synthesis import GearResult  # noqa: E402
from transplanter.geometry.poses import rotate_about  # noqa: E402
from transplanter.gears.rack_teeth import ADDENDUM  # noqa: E402


def plot_mesh(result: GearResult, path: str, positions: int = 4):
    """The pair at ``positions`` driver angles: driver turns clockwise, driven counterclockwise."""
    d = result.design
    shapes = outlines(result)
    fig, axes = plt.subplots(1, positions, figsize=(4 * positions, 4.2))
    for ax, k in zip(axes, np.linspace(0, len(d.phi1) - 1, positions, endpoint=False).astype(int)):
        ax.fill(*rotate_about(shapes["driver"], (0.0, 0.0), -d.phi1[k]).T, color="tab:blue", alpha=0.35, lw=0.6, ec="tab:blue")
        driven = rotate_about(shapes["driven"], (0.0, 0.0), d.phi2[k]) + [d.center_distance, 0]
        ax.fill(*driven.T, color="tab:orange", alpha=0.35, lw=0.6, ec="tab:orange")
        ax.plot([0, d.center_distance], [0, 0], "k+", ms=8)
        ax.plot(d.radius[0][k], 0, "r.", ms=5)
        ax.set_title(f"phi1 = {np.degrees(d.phi1[k]):.0f} deg", fontsize=9)
        ax.set_aspect("equal")
        ax.axis("off")
    fig.suptitle(result.problem.title or result.problem.source, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_kinematics(result: GearResult, path: str):
    d = result.design
    phi = np.degrees(d.phi1)
    fig, axes = plt.subplots(3, 1, figsize=(7, 7), sharex=True)
    axes[0].plot(phi, d.ratio)
    axes[0].set_ylabel("ratio i12 = ω1/ω2")
    axes[1].plot(phi, d.driven_speed)
    axes[1].set_ylabel("ω2 / rad s⁻¹")
    axes[2].plot(phi, d.driven_acceleration)
    axes[2].set_ylabel("α2 / rad s⁻²")
    axes[2].set_xlabel(f"driver angle φ1 / deg (ω1 = {d.driver_speed:.3f} rad/s)")
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_curvature(result: GearResult, path: str):
    d = result.design
    fig, ax = plt.subplots(figsize=(7, 4))
    for gear, name in enumerate(("driver", "driven")):
        rho = np.where(d.convexity[gear] > 0, d.curvature_radius[gear], np.nan)
        ax.plot(np.degrees(d.phi1), rho, label=f"{name} (convex parts)")
    if result.problem.module is not None:
        limit = ADDENDUM * result.problem.module / np.sin(result.problem.pressure_angle) ** 2
        ax.axhline(limit, color="r", ls="--", lw=1, label=f"rack undercut limit m/sin²α = {limit:.2f} mm")
    ax.set_xlabel("driver angle φ1 at the contact point / deg")
    ax.set_ylabel("curvature radius / mm")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_gear_figures(result: GearResult, folder) -> list[str]:
    names = ["gear_mesh.png", "gear_kinematics.png", "gear_curvature.png"]
    for name, plot in zip(names, (plot_mesh, plot_kinematics, plot_curvature)):
        plot(result, str(folder / name))
    return names

"""One cycle of the designed onion transplanter as a GIF, drawn by blitting (``moving_picture``).

Left, the machine's frame (mm): the gear pair turning (driver clockwise by phi1 about O1, driven
counterclockwise by phi2 about O, as the gear library draws them; tooth outlines when cut), the
crank O2A, the parallelogram O2-A-B-D, the coupler on to C and the duckbill CE. Right, the field
(mm): the path of E being drawn as the machine travels, with the depth window of the cycle.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.figure import Figure

from transplanter.api_arguments import require_result
from transplanter.gears.drawings import outlines
from transplanter.geometry.poses import rotate_about
from transplanter.moving_picture import blitted_frames, write_gif
from transplanter.output_folder import writable_folder
from transplanter.parallelogram.kinematics import mechanisms
from transplanter.parallelogram.result import ParallelogramResult
from transplanter.parallelogram.trajectory import measure, sample_path

FRAMES = 72
FIGURE_SIZE = (10.0, 4.8)


def _draw_frames(result: ParallelogramResult, frames: int):
    problem, design = result.problem, result.final
    mech = mechanisms(problem, design)
    path = sample_path(mech, 1, frames + 1)
    fine = sample_path(mech, 1, 721)
    m = measure(mech, problem.depth_window, 8192)
    a = float(mech.center_distance[0])
    # the drawn pair is the toothed one, brought back to the design's size
    scale = result.gear.design.driver.scale
    shapes = {name: outline / scale for name, outline in outlines(result.gear).items()}
    pivot = np.array([a, 0.0]) + problem.crank_pivot
    offset = np.array([design["l2"], 0.0])
    tool = np.array([design["l2"] + design["l5"], 0.0])

    fig = Figure(figsize=FIGURE_SIZE, layout="constrained")
    machine, field = fig.subplots(1, 2, width_ratios=[1.1, 1])
    driver_line, = machine.plot([], [], color="tab:blue", lw=0.7, animated=True, label="driver gear")
    driven_line, = machine.plot([], [], color="tab:orange", lw=0.7, animated=True, label="driven gear")
    links, = machine.plot([], [], "k-o", ms=3, lw=1.5, animated=True, label="O2-A-B-D, B-C-E")
    tip, = machine.plot([], [], "rv", ms=6, animated=True, label="planting point E")
    relative = fine.tip - np.array([[problem.forward_velocity], [0.0]]) * fine.time
    machine.plot(*relative, color="0.8", lw=0.8, label="E relative to the machine")
    machine.plot([0, a, pivot[0]], [0, 0, pivot[1]], "k+", ms=8)
    reach = np.vstack([np.linalg.norm(s, axis=1).max() for s in shapes.values()]).max()
    corners = np.vstack([relative.T, [[-reach, -reach], [a + reach, reach]], (pivot + offset)[None]])
    pad = 0.05 * np.ptp(corners, axis=0).max()
    machine.set(xlim=(corners[:, 0].min() - pad, corners[:, 0].max() + pad),
                ylim=(corners[:, 1].min() - pad, corners[:, 1].max() + pad), aspect="equal",
                xlabel="x / mm (machine)", ylabel="y / mm", title="gears and parallelogram")
    machine.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.14), ncols=2)

    field.plot(*fine.tip, color="0.8", lw=0.8)
    window = mech.state(np.linspace(m.window[0, 0], m.window[1, 0], 200)[None, :])[1][:, 0]
    field.plot(*window, color="tab:red", lw=2.5, label=f"depth window (H = {m.depth[0]:.1f} mm)")
    trace, = field.plot([], [], "k-", lw=1.2, animated=True, label="E so far")
    clock = field.text(0.0, 1.03, "", transform=field.transAxes, fontsize=9, va="bottom", animated=True)
    field.set(aspect="equal", xlabel="x / mm (field)", ylabel="y / mm")
    field.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.26))

    def draw(k: int):
        phi1, phi2 = path.driver_angle[k], float(mech.driven_angle(np.array([path.driver_angle[k] % (2 * np.pi)]))[0])
        driver_line.set_data(*rotate_about(shapes["driver"], (0.0, 0.0), -phi1).T)
        driven_line.set_data(*(rotate_about(shapes["driven"], (0.0, 0.0), phi2) + [a, 0.0]).T)
        pin = path.crank_pin[:, k]
        chain = np.array([pivot, pin, pin + offset, pivot + offset, pin + offset, pin + tool,
                          pin + tool + [0.0, -design["l6"]]])
        links.set_data(*chain.T)
        tip.set_data([chain[-1, 0]], [chain[-1, 1]])
        trace.set_data(*path.tip[:, :k + 1])
        clock.set_text(f"t = {path.time[k]:.3f} s, driver turn {np.degrees(phi1):5.1f} deg")
        return [driver_line, driven_line, links, tip, trace, clock]

    return fig, draw


def write_animation(result: ParallelogramResult, folder: str | Path, frames: int = FRAMES) -> Path:
    """``animation.gif`` of one driver turn (one plant) in ``folder``."""
    require_result(result, ParallelogramResult, "parallelogram")
    folder = writable_folder(folder)
    fig, draw = _draw_frames(result, frames)
    return write_gif(blitted_frames(fig, draw, frames), folder / "animation.gif")

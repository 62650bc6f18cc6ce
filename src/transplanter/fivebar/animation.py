"""One turn of a designed five-bar as a moving picture: GIF through Pillow, MP4 where ffmpeg exists.

The still parts are drawn once; each frame redraws only the moving artists (``moving_picture``).

Left, the ground frame (mm): the linkage O-A-F-E-B and the push plate E-F-P moving, P's path
over the turn (from the verification) traced up to the frame, the key poses marked, the pitch
curves turning on the carrier, and with a seedling support its cam, arm C-K and C-G-H-Z moving with the
carrier. Right, the carrier frame (mm): the four pitch curves meshing, and
tooth outlines when given. Hinges and plate come from ``loop_closure``, gear turns from the design
(``gears_on_carrier``).
"""
from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
from matplotlib.figure import Figure
from PIL import Image

from transplanter.api_arguments import require_result
from transplanter.figure_conventions import LEGEND_BESIDE
from transplanter.fivebar.gears_on_carrier import carrier_to_world, gears_on_carrier
from transplanter.fivebar.loop_closure import close_loop
from transplanter.fivebar.result import FiveBarResult
from transplanter.geometry.poses import rotation
from transplanter.moving_picture import blitted_frames, write_gif, write_mp4
from transplanter.output_folder import writable_folder

#: Frames per turn: one turn in 6 s at ``moving_picture.FPS``, written in about 2 s.
FRAMES = 72
FIGURE_SIZE = (9.0, 4.8)

#: Tooth outlines by gear name: (outline (N, 2) mm in the gear's frame, centre (2,) mm in the carrier
#: frame, the gear's turn (rad, counterclockwise in the carrier frame) as a function of the carrier turn).
Teeth = dict[str, tuple[np.ndarray, np.ndarray, Callable[[np.ndarray], np.ndarray]]]


def _placed(outline: np.ndarray, center: np.ndarray, turn: float) -> np.ndarray:
    return center + outline @ rotation(turn).T


#: The clock below the carrier frame: its fixed words drawn once, the turn after them redrawn each frame.
CLOCK_WORDS = "carrier turn (clockwise from pose 1):"


def _clock_text(c: float) -> str:
    return f" {np.degrees(c):5.1f} deg"


def _draw_frames(result: FiveBarResult, teeth: Teeth | None, frames: int) -> tuple[Figure, Callable[[int], list]]:
    """The Figure and a function that draws frame k."""
    mech, problem, check = result.design.mech, result.problem, result.verification
    turns = np.linspace(0, 2 * np.pi, frames, endpoint=False)
    state = close_loop(mech, turns, result.design.relative_angle.evaluate(turns))
    gears = gears_on_carrier(result.train, float(mech.carrier_length))
    # each gear's turn (rad) at every frame, evaluated at once
    outlines = [(g.pitch_curve, g.center, np.asarray(g.angle(turns)), g.name.replace("_", " ")) for g in gears]
    toothed = [(outline, center, np.asarray(angle(turns)), name)
               for name, (outline, center, angle) in (teeth or {}).items()]

    fig = Figure(figsize=FIGURE_SIZE, layout="constrained")
    world, carrier = fig.subplots(1, 2, width_ratios=[1, 1.5])
    world.plot(*check.trajectory.T, color="0.75", lw=1, label="P over a turn")
    trace, = world.plot([], [], "k-", lw=1.5, label="P so far", animated=True)
    world.plot(*problem.poses[:, :2].T, "r^", ms=6, label="key poses")
    for label, pose in zip(problem.labels, problem.poses, strict=True):
        world.annotate(f" {label}", pose[:2], fontsize=8, color="r", parse_math=False)
    chain, = world.plot([], [], "b-o", ms=3, lw=1.5, label="O-A-F-E-B", animated=True)
    plate, = world.fill([], [], color="tab:green", alpha=0.5, label="plate E-F-P", animated=True)
    world_gears = [world.plot([], [], lw=0.8, animated=True)[0] for _ in outlines]
    gear_reach = max(np.linalg.norm(g.center) + np.linalg.norm(g.pitch_curve, axis=1).max() for g in gears)
    support, moving_support = result.support, []
    extent = [check.trajectory, gear_reach * np.array([[-1, -1], [1, 1]]), mech.hinge_b[None], state["e"], state["f"]]
    if support is not None:
        joints = support.joints(turns)
        moving_support = [world.plot([], [], "m-o", ms=3, lw=1.5, label="support C-G-H-Z", animated=True)[0],
                          world.plot([], [], "c-o", ms=3, lw=1.2, label="arm C-K", animated=True)[0],
                          world.plot([], [], "k-", lw=0.8, label="support cam", animated=True)[0]]
        extent += [joints[name] for name in "CGHZ"] + [support.cam_outline(0.0)]
    every = np.vstack(extent)
    low, high = np.nanmin(every, axis=0), np.nanmax(every, axis=0)
    pad = 0.05 * (high - low).max()
    world.set(xlim=(low[0] - pad, high[0] + pad), ylim=(low[1] - pad, high[1] + pad), aspect="equal",
              xlabel="x (mm)", ylabel="y (mm)", title="ground frame")
    world.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.12), ncols=2)

    carrier_curves = [carrier.plot([], [], lw=1, label=name, animated=True)[0] for *_, name in outlines]
    carrier_teeth = [carrier.plot([], [], "k-", lw=0.6, animated=True)[0] for _ in toothed]
    words = carrier.text(0.0, -0.22, CLOCK_WORDS, transform=carrier.transAxes, ha="left", va="top",
                         fontsize=9)      # below the axis label, where constrained layout keeps room for it
    clock = carrier.annotate(_clock_text(0.0), (1.0, 0.0), xycoords=words, ha="left", va="bottom", fontsize=9,
                             animated=True)
    centers = np.array([g.center for g in gears])
    carrier.plot(*centers.T, "k+")
    carrier.plot(*centers[[0, 1, 3]].T, "k:", lw=0.8)
    reach = max(np.linalg.norm(g.pitch_curve, axis=1).max() for g in gears)
    carrier.set(xlim=(centers[:, 0].min() - 1.2 * reach, centers[:, 0].max() + 1.2 * reach),
                ylim=(centers[:, 1].min() - 1.2 * reach, centers[:, 1].max() + 1.2 * reach), aspect="equal",
                xlabel="x along the carrier O-A (mm)", ylabel="y on the carrier (mm)",
                title="pitch curves on the carrier" + (" with teeth" if toothed else ""))
    carrier.legend(fontsize=7, **LEGEND_BESIDE)

    def draw(k: int):
        c = turns[k]
        upto = check.carrier_turns <= c
        trace.set_data(*check.trajectory[upto].T)
        hinges = np.array([[0.0, 0.0], state["a"][k], state["f"][k], state["e"][k], mech.hinge_b])
        chain.set_data(*hinges.T)
        plate.set_xy(np.array([state["e"][k], state["f"][k], state["p"][k]]))
        for line, world_line, (outline, center, angles, _) in zip(carrier_curves, world_gears, outlines, strict=True):
            placed = _placed(outline, center, angles[k])
            line.set_data(*placed.T)
            world_line.set_data(*carrier_to_world(mech, placed, c).T)
        for line, (outline, center, angles, _) in zip(carrier_teeth, toothed, strict=True):
            line.set_data(*_placed(outline, center, angles[k]).T)
        clock.set_text(_clock_text(c))
        if support is not None and moving_support:
            moving_support[0].set_data(*np.array([joints[name][k] for name in "CGHZ"]).T)
            moving_support[1].set_data(*np.array([joints["C"][k], joints["K"][k]]).T)
            moving_support[2].set_data(*support.cam_outline(c).T)
        return [trace, chain, plate, clock, *world_gears, *carrier_curves, *carrier_teeth, *moving_support]

    return fig, draw


def render_frames(result: FiveBarResult, teeth: Teeth | None = None, frames: int = FRAMES) -> list[Image.Image]:
    """The frames of one turn as RGB images (``FIGURE_SIZE`` at ``moving_picture.DPI``)."""
    return blitted_frames(*_draw_frames(result, teeth, frames), frames)


def write_animation(result: FiveBarResult, folder: str | Path, teeth: Teeth | None = None,
                    frames: int = FRAMES) -> list[Path]:
    """``animation.gif`` (Pillow) of one turn in ``folder``, and ``animation.mp4`` where ffmpeg exists.

    Parameters
    ----------
    result : FiveBarResult
        From ``fivebar.synthesize``.
    folder : str or Path
        Output folder (made if missing).
    teeth : dict, optional
        Tooth outlines by gear name (see ``Teeth``), drawn over the pitch curves.
    frames : int
        Frames per turn.

    Returns
    -------
    list of Path
        The files written.
    """
    require_result(result, FiveBarResult, "fivebar")
    folder = writable_folder(folder)
    images = render_frames(result, teeth, frames)
    written = [write_gif(images, folder / "animation.gif"), write_mp4(images, folder / "animation.mp4")]
    return [path for path in written if path]

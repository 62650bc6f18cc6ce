"""One carrier turn of the pick-up mechanism as a GIF (Pillow): the bent carrier O-O1-O2, the arm to the
needle tip, the three shafts' pitch curves turning, and the tip's path traced up to the frame."""
from __future__ import annotations

from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from PIL import Image

from transplanter.api_arguments import require_result
from transplanter.gears.pair import driven_angle
from transplanter.geometry.poses import rotation
from transplanter.output_folder import writable_folder
from transplanter.pickup.result import PickupResult

FRAMES, FPS, DPI = 48, 12, 70


def write_animation(result: PickupResult, folder: str | Path, frames: int = FRAMES) -> Path:
    """Write ``pickup.gif`` into ``folder``; the path written."""
    require_result(result, PickupResult, "pickup")
    p = result.problem
    one, two = result.stage_one, result.stage_two
    fig = Figure(figsize=(6, 6), layout="constrained")
    canvas = FigureCanvasAgg(fig)
    ax = fig.subplots()
    reach = p.first_length + p.second_length + p.arm_length
    ax.set_xlim(-reach, reach)
    ax.set_ylim(-reach, reach)
    ax.set_aspect("equal")
    ax.set_xlabel("x / mm")
    ax.set_ylabel("y / mm")
    sun = one.points[0] @ rotation(p.start).T
    ax.plot(*sun.T, color="0.5", lw=1)
    link, = ax.plot([], [], "k-o", lw=2, ms=4)
    path, = ax.plot([], [], color="tab:blue", lw=1)
    gear2, = ax.plot([], [], color="tab:orange", lw=1)
    gear3, = ax.plot([], [], color="tab:green", lw=1)
    gear4, = ax.plot([], [], color="tab:red", lw=1)
    images = []
    step = max(1, len(result.carrier_turns) // frames)
    for k in range(0, len(result.carrier_turns), step):
        c = result.carrier_turns[k]
        carrier = p.start + c
        o1 = p.first_length * np.array([np.cos(carrier), np.sin(carrier)])
        o2 = o1 + p.second_length * np.array([np.cos(carrier + p.bend), np.sin(carrier + p.bend)])
        tip = result.tip[k]
        link.set_data([0, o1[0], o2[0], tip[0]], [0, o1[1], o2[1], tip[1]])
        path.set_data(*result.tip[:k + 1].T)
        chi = float(driven_angle(one, np.array([c]))[0])
        # gear 2 about O1: its contact faces O at the start, turned by chi with the carrier
        gear2.set_data(*(o1 + one.points[1] @ rotation(carrier + chi).T).T)
        # gear 3 (stage 2's mirrored driver, reflected back) about O1, facing O2 at the start
        mirror = two.points[0] * [1, -1]
        gear3.set_data(*(o1 + mirror @ rotation(carrier + p.bend + chi).T).T)
        planet = two.points[1] * [1, -1]
        gear4.set_data(*(o2 + planet @ rotation(carrier + p.bend + result.planet_turn[k]).T).T)
        ax.set_title(f"carrier turn {np.degrees(c):5.1f} deg", fontsize=9)
        canvas.draw()
        images.append(Image.fromarray(np.asarray(canvas.buffer_rgba())[..., :3]).quantize(64))
    target = writable_folder(folder) / "pickup.gif"
    images[0].save(target, save_all=True, append_images=images[1:], duration=int(1000 / FPS), loop=0)
    return target

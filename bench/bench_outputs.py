"""Time the main job's drawings.pdf and animation against the former writers, kept below.

    python bench/bench_outputs.py

The main job's design (examples/vegetable_planting.toml) is synthesised once; then, in this process, each side
best of three on the same nine sheets and the same design:

- drawings.pdf: the package (``drawing.pdf``: the sheets ``fivebar.drawings`` makes, drawn from memory by
  ``drawing.sheet_page``, one LineCollection per colour and line type, texts as text) against the former writer
  (each sheet's DXF read back and drawn by ezdxf's drawing add-on on matplotlib: texts as filled glyph paths, a
  patch per filled shape, each widening the axes' limits);
- the animation with the main job's teeth: ``fivebar.animation.write_animation`` against the former frames
  (each gear's turn evaluated per frame and per artist, the whole clock text redrawn each frame), written by the
  same GIF writer.

It prints both ratios and the absolute times (target: drawings.pdf under 1 s), and ``write_drawings`` whole.
"""
from __future__ import annotations

import tempfile
from functools import partial
from pathlib import Path

import ezdxf
import numpy as np
from best_time import best_time
from ezdxf.addons.drawing import Frontend, RenderContext
from ezdxf.addons.drawing.config import BackgroundPolicy, Configuration
from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure

from transplanter import fivebar
from transplanter.drawing.pdf import PAGE_INCHES, write_pdf
from transplanter.figure_conventions import LEGEND_BESIDE
from transplanter.fivebar import animation
from transplanter.fivebar.drawings import write_drawings
from transplanter.fivebar.gears_on_carrier import carrier_to_world, gears_on_carrier, teeth_on_carrier
from transplanter.fivebar.loop_closure import close_loop
from transplanter.geometry.poses import rotation
from transplanter.moving_picture import blitted_frames, write_gif

ROOT = Path(__file__).resolve().parents[1]
REPEAT = 3


# --- the former writers, the baselines ---

def former_write_pdf(sheets, path: Path) -> Path:
    """Each DXF read back and drawn by ezdxf's drawing add-on on matplotlib, a page each."""
    config = Configuration(background_policy=BackgroundPolicy.WHITE)
    with PdfPages(path, metadata={"CreationDate": None}) as pages:
        for sheet in sheets:
            document = ezdxf.readfile(sheet)
            figure = Figure(figsize=PAGE_INCHES)
            axes = figure.add_axes((0.02, 0.02, 0.96, 0.92))
            Frontend(RenderContext(document), MatplotlibBackend(axes), config=config).draw_layout(
                document.modelspace())
            axes.set_aspect("equal")
            axes.set_axis_off()
            figure.suptitle(f"{sheet.name} (millimetres)")
            pages.savefig(figure)
    return path


def _former_placed(outline, center, angle, c):
    return center + outline @ rotation(float(np.asarray(angle(np.array([c])))[0])).T


def _former_clock_text(c):
    return f"carrier turn {np.degrees(c):5.1f} deg (clockwise from pose 1)"


def former_draw_frames(result, teeth, frames):
    """The former figure and frame function (no seedling support: the main job has none)."""
    mech, problem, check = result.design.mech, result.problem, result.verification
    turns = np.linspace(0, 2 * np.pi, frames, endpoint=False)
    state = close_loop(mech, turns, result.design.relative_angle.evaluate(turns))
    gears = gears_on_carrier(result.train, float(mech.carrier_length))
    outlines = [(g.pitch_curve, g.center, g.angle, g.name.replace("_", " ")) for g in gears]
    toothed = [(outline, center, angle, name) for name, (outline, center, angle) in teeth.items()]
    fig = Figure(figsize=animation.FIGURE_SIZE, layout="constrained")
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
    every = np.vstack([check.trajectory, gear_reach * np.array([[-1, -1], [1, 1]]), mech.hinge_b[None], state["e"],
                       state["f"]])
    low, high = np.nanmin(every, axis=0), np.nanmax(every, axis=0)
    pad = 0.05 * (high - low).max()
    world.set(xlim=(low[0] - pad, high[0] + pad), ylim=(low[1] - pad, high[1] + pad), aspect="equal",
              xlabel="x (mm)", ylabel="y (mm)", title="ground frame")
    world.legend(fontsize=7, loc="upper left", bbox_to_anchor=(0, -0.12), ncols=2)
    carrier_curves = [carrier.plot([], [], lw=1, label=name, animated=True)[0] for *_, name in outlines]
    carrier_teeth = [carrier.plot([], [], "k-", lw=0.6, animated=True)[0] for _ in toothed]
    clock = carrier.text(0.0, -0.22, _former_clock_text(0.0), transform=carrier.transAxes, ha="left", va="top",
                         fontsize=9, animated=True)
    centers = np.array([g.center for g in gears])
    carrier.plot(*centers.T, "k+")
    carrier.plot(*centers[[0, 1, 3]].T, "k:", lw=0.8)
    reach = max(np.linalg.norm(g.pitch_curve, axis=1).max() for g in gears)
    carrier.set(xlim=(centers[:, 0].min() - 1.2 * reach, centers[:, 0].max() + 1.2 * reach),
                ylim=(centers[:, 1].min() - 1.2 * reach, centers[:, 1].max() + 1.2 * reach), aspect="equal",
                xlabel="x along the carrier O-A (mm)", ylabel="y on the carrier (mm)",
                title="pitch curves on the carrier with teeth")
    carrier.legend(fontsize=7, **LEGEND_BESIDE)

    def draw(k):
        c = turns[k]
        trace.set_data(*check.trajectory[check.carrier_turns <= c].T)
        chain.set_data(*np.array([[0.0, 0.0], state["a"][k], state["f"][k], state["e"][k], mech.hinge_b]).T)
        plate.set_xy(np.array([state["e"][k], state["f"][k], state["p"][k]]))
        for line, (outline, center, angle, _) in zip(carrier_curves, outlines, strict=True):
            line.set_data(*_former_placed(outline, center, angle, c).T)
        for line, (outline, center, angle, _) in zip(world_gears, outlines, strict=True):
            line.set_data(*carrier_to_world(mech, _former_placed(outline, center, angle, c), c).T)
        for line, (outline, center, angle, _) in zip(carrier_teeth, toothed, strict=True):
            line.set_data(*_former_placed(outline, center, angle, c).T)
        clock.set_text(_former_clock_text(c))
        return [trace, chain, plate, clock, *world_gears, *carrier_curves, *carrier_teeth]

    return fig, draw


def former_write_animation(result, folder: Path, teeth) -> Path:
    images = blitted_frames(*former_draw_frames(result, teeth, animation.FRAMES), animation.FRAMES)
    return write_gif(images, folder / "animation.gif")


# --- the comparison ---

def _row(what: str, package_s: float, former_s: float) -> None:
    print(f"{what:<14} package {package_s:6.3f} s   former {former_s:6.3f} s   "
          f"former/package {former_s / package_s:5.1f}x")


def main():
    result = fivebar.synthesize(fivebar.load_problem(ROOT / "examples/vegetable_planting.toml"))
    teeth = teeth_on_carrier(result.toothed, float(result.design.mech.carrier_length))
    with tempfile.TemporaryDirectory() as scratch:
        folder = Path(scratch)
        drawings_s, written = best_time(partial(write_drawings, result, folder), REPEAT)
        sheets = [path for path in written if path.suffix == ".dxf"]
        pages = [(path.name, ezdxf.readfile(path)) for path in sheets]
        pdf_s, _ = best_time(partial(write_pdf, pages, folder / "package.pdf"), REPEAT)
        former_pdf_s, _ = best_time(partial(former_write_pdf, sheets, folder / "former.pdf"), REPEAT)
        animation_s, _ = best_time(partial(animation.write_animation, result, folder, teeth), REPEAT)
        former_animation_s, _ = best_time(partial(former_write_animation, result, folder, teeth), REPEAT)
    print(f"main job's outputs, best of {REPEAT} each, one process ({len(sheets)} sheets, {animation.FRAMES} frames)")
    _row("drawings.pdf", pdf_s, former_pdf_s)
    _row("animation", animation_s, former_animation_s)
    print(f"write_drawings whole (sheets, SVGs, drawings.pdf, parts.csv, tables): {drawings_s:.3f} s")


if __name__ == "__main__":
    main()

"""Time the main job's drawings.pdf, animation and figures against the former writers, kept below.

    python bench/bench_outputs.py

The main job's design (examples/vegetable_planting.toml) is synthesised once; then, in this process, each side
best of three on the same nine sheets and the same design:

- drawings.pdf: the package (``drawing.pdf``: the sheets ``fivebar.drawings`` makes, drawn from memory by
  ``drawing.sheet_page``, one LineCollection per colour and line type, texts as text) against the former writer
  (each sheet's DXF read back and drawn by ezdxf's drawing add-on on matplotlib: texts as filled glyph paths, a
  patch per filled shape, each widening the axes' limits);
- the animation with the main job's teeth: ``fivebar.animation.write_animation`` against the former frames
  (the same figure with the former's per-frame work: each gear's turn evaluated per frame and per artist, the
  whole clock text redrawn each frame), written by the same GIF writer;
- the figures (the ten PNGs of ``draw_figures``, drawn and laid out once): saved as the command line saves
  them (``cli``'s PNGs at zlib level ``PNG_COMPRESSION``) against matplotlib's default level (6), the sides in
  turn, with both sides' sizes.

It prints both ratios and the absolute times (target: drawings.pdf under 1 s), and ``write_drawings`` whole.
"""
from __future__ import annotations

import tempfile
from functools import partial
from pathlib import Path
from unittest import mock

import ezdxf
import numpy as np
from best_time import best_time
from ezdxf.addons.drawing import Frontend, RenderContext
from ezdxf.addons.drawing.config import BackgroundPolicy, Configuration
from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure

from transplanter import cli, fivebar
from transplanter.drawing.pdf import PAGE_INCHES, write_pdf
from transplanter.fivebar import animation
from transplanter.fivebar.drawings import write_drawings
from transplanter.fivebar.gears_on_carrier import gears_on_carrier, teeth_on_carrier
from transplanter.geometry.poses import rotation
from transplanter.moving_picture import blitted_frames, write_gif

ROOT = Path(__file__).resolve().parents[1]
REPEAT = 3
#: Rounds of the figures' comparison (each side once a round).
FIGURE_ROUNDS = 6


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


def former_write_animation(result, folder: Path, teeth) -> Path:
    """The former frames: the same figure, with the former's per-frame work: each gear's turn evaluated at the
    frame's carrier turn once per artist that draws it (pitch curve on the carrier, in the ground frame, teeth)
    and the whole clock text drawn each frame (its words not in the still background); a lower bound: the
    former also placed each pitch curve twice a frame."""
    frames = animation.FRAMES
    turns = np.linspace(0, 2 * np.pi, frames, endpoint=False)
    angles = [gear.angle for gear in gears_on_carrier(result.train, float(result.design.mech.carrier_length))] * 2
    angles += [angle for _, _, angle in teeth.values()]
    with mock.patch.object(animation, "CLOCK_WORDS", ""), \
            mock.patch.object(animation, "_clock_text", _former_clock_text):
        figure, draw = animation._draw_frames(result, teeth, frames)

    def former_draw(k):
        for angle in angles:
            rotation(float(np.asarray(angle(np.array([turns[k]])))[0]))
        return draw(k)

    return write_gif(blitted_frames(figure, former_draw, frames), folder / "animation.gif")


def _former_clock_text(c):
    return f"carrier turn {np.degrees(c):5.1f} deg (clockwise from pose 1)"


# --- the comparison ---

def package_save_figures(figures: dict, folder: Path) -> None:
    for stem, figure in figures.items():
        cli._save_figure(figure, folder / f"{stem}.png", dpi=120)


def former_save_figures(figures: dict, folder: Path) -> None:
    for stem, figure in figures.items():
        figure.savefig(folder / f"{stem}.png", dpi=120)


def _size_kb(folder: Path) -> float:
    return sum(path.stat().st_size for path in folder.glob("*.png")) / 1024


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
        figures = result.draw_figures()
        (folder / "package").mkdir()
        (folder / "former").mkdir()
        former_save_figures(figures, folder / "former")     # the first save lays the figures out, for both sides
        # sides in turn, round by round: this machine's speed drifts by tens of percent within a minute
        rounds = [(best_time(partial(package_save_figures, figures, folder / "package"), 1)[0],
                   best_time(partial(former_save_figures, figures, folder / "former"), 1)[0])
                  for _ in range(FIGURE_ROUNDS)]
        figures_s, former_figures_s = np.min(rounds, axis=0)
        faster = sum(package < former for package, former in rounds)
        sizes = _size_kb(folder / "package"), _size_kb(folder / "former")
    print(f"main job's outputs, best of {REPEAT} each, one process ({len(sheets)} sheets, {animation.FRAMES} frames)")
    _row("drawings.pdf", pdf_s, former_pdf_s)
    _row("animation", animation_s, former_animation_s)
    _row("figures (PNG)", figures_s, former_figures_s)
    print(f"  best of {FIGURE_ROUNDS} rounds, the sides in turn; the package faster in {faster} of them")
    print(f"  {len(figures)} PNGs: package {sizes[0]:.0f} KB (zlib level {cli.PNG_COMPRESSION}), "
          f"former {sizes[1]:.0f} KB (level 6)")
    print(f"write_drawings whole (sheets, SVGs, drawings.pdf, parts.csv, tables): {drawings_s:.3f} s")


if __name__ == "__main__":
    main()

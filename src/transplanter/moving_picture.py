"""Moving pictures of a job: frames blitted on the Agg canvas, written as a GIF (Pillow) and, where
ffmpeg exists, an MP4.

The still parts of a figure are drawn once; each frame restores that background and redraws only
the moving artists, which keeps a cycle to a few seconds.
"""
from __future__ import annotations

import shutil
import subprocess
from collections.abc import Callable, Iterable
from pathlib import Path

from matplotlib.artist import Artist
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure
from PIL import Image

#: Frame rate and resolution: 72 frames play in 6 s, about 0.5 MB.
FPS = 12
DPI = 80
#: Colours of the GIF palette (a dozen line colours and their antialiased blends).
PALETTE_COLORS = 64


def blitted_frames(fig: Figure, draw: Callable[[int], Iterable[Artist]], frames: int) -> list[Image.Image]:
    """RGB images of ``frames`` frames at ``DPI``; ``draw(k)`` moves the artists of frame k and returns them."""
    canvas = FigureCanvasAgg(fig)
    fig.set_dpi(DPI)
    canvas.draw()                       # lays out and draws the still parts (moving ones are animated)
    background = canvas.copy_from_bbox(fig.bbox)
    images = []
    for k in range(frames):
        canvas.restore_region(background)
        for artist in draw(k):
            fig.draw_artist(artist)
        images.append(Image.frombuffer("RGBA", canvas.get_width_height(), canvas.buffer_rgba()).convert("RGB"))
    return images


def write_gif(images: list[Image.Image], path: Path) -> Path:
    """The frames as a looping GIF at ``FPS``, all on the first frame's palette."""
    palette = images[0].quantize(PALETTE_COLORS, method=Image.Quantize.FASTOCTREE)
    indexed = [image.quantize(palette=palette, dither=Image.Dither.NONE) for image in images]
    indexed[0].save(path, save_all=True, append_images=indexed[1:], duration=round(1000 / FPS), loop=0)
    return path


def write_mp4(images: list[Image.Image], path: Path) -> Path | None:
    """The frames as an H.264 MP4 at ``FPS`` when ffmpeg is on the PATH; None (nothing written) otherwise."""
    ffmpeg = shutil.which("ffmpeg")
    if not ffmpeg:
        return None
    width, height = images[0].size
    subprocess.run([ffmpeg, "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "rgb24", "-s",
                    f"{width}x{height}", "-r", str(FPS), "-i", "-", "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                    "-pix_fmt", "yuv420p", str(path)], input=b"".join(image.tobytes() for image in images),
                   check=True)
    return path

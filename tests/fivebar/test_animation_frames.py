"""The animation's frames: a frame blitted over the still background is the whole figure drawn at that carrier
turn, and the clock names the frame's turn."""
import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from PIL import Image, ImageChops

from transplanter.fivebar.animation import _draw_frames, render_frames
from transplanter.moving_picture import DPI

FRAMES = 4


def _changed(first: Image.Image, second: Image.Image) -> float:
    """The fraction of pixels that differ."""
    return float((np.asarray(ImageChops.difference(first, second)).max(axis=2) > 0).mean())


def test_a_blitted_frame_is_the_whole_figure_drawn_at_its_turn(example_result):
    blitted = render_frames(example_result, frames=FRAMES)
    figure, draw = _draw_frames(example_result, None, FRAMES)
    canvas = FigureCanvasAgg(figure)
    figure.set_dpi(DPI)
    canvas.draw()                            # the layout of the animation, then kept as it is
    figure.set_layout_engine("none")
    moving = draw(2)
    for artist in moving:
        artist.set_animated(False)
    canvas.draw()
    whole = Image.frombuffer("RGBA", canvas.get_width_height(), canvas.buffer_rgba()).convert("RGB")
    # the whole figure draws the moving artists among the still ones by z-order, the blit over them: only where
    # they cross may pixels differ, a small share of what one frame's step moves
    assert _changed(whole, blitted[2]) < 0.1 * _changed(whole, blitted[1])
    clock = next(artist for artist in moving if hasattr(artist, "get_text") and "deg" in artist.get_text())
    assert clock.get_text().split() == [f"{360 * 2 / FRAMES:.1f}", "deg"]

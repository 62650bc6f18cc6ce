"""A part's outline as an SVG in millimetres, for a quick look or a laser cutter."""
from __future__ import annotations

from pathlib import Path

import numpy as np


def write_svg(outline: np.ndarray, path: Path, *, pitch_curve: np.ndarray | None = None,
              bore: np.ndarray | None = None, mark: np.ndarray | None = None) -> Path:
    """Outline (N, 2) mm as an SVG in mm; optionally the pitch curve (M, 2) dashed, the bore's closed outline
    (K, 2) and the assembly mark (2, 2) mm."""
    margin = 5.0
    low, high = outline.min(axis=0) - margin, outline.max(axis=0) + margin
    width, height = high - low

    # SVG's y axis points down: flip so the drawing matches the mathematical frame.
    def svg_points(points):
        return " ".join(f"{x - low[0]:.6f},{high[1] - y:.6f}" for x, y in points)

    extras = ""
    if pitch_curve is not None:
        extras += (f'  <polyline points="{svg_points(pitch_curve)}" fill="none" stroke="blue" stroke-width="0.1" '
                   f'stroke-dasharray="1,0.5"/>\n')
    if bore is not None:
        extras += f'  <polygon points="{svg_points(bore)}" fill="none" stroke="red" stroke-width="0.1"/>\n'
    if mark is not None:
        extras += f'  <polyline points="{svg_points(mark)}" fill="none" stroke="green" stroke-width="0.2"/>\n'
    path.write_text(
        f'<svg xmlns="http://www.w3.org/2000/svg" width="{width:.3f}mm" height="{height:.3f}mm" '
        f'viewBox="0 0 {width:.6f} {height:.6f}">\n'
        f'  <polygon points="{svg_points(outline)}" fill="none" stroke="black" stroke-width="0.1"/>\n'
        f'{extras}</svg>\n')
    return path

"""Conventions every figure of the package follows, kept in one place so the figures look alike."""
from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: One figure, drawn when called: what a result's ``figure_drawers`` gives per file stem.
FigureDrawer = Callable[[], "Figure"]

#: ``Axes.legend`` keywords that put the legend beside the axes, off the data (constrained layout makes room).
LEGEND_BESIDE: dict[str, Any] = {"loc": "upper left", "bbox_to_anchor": (1.02, 1), "borderaxespad": 0}
#: ``set_title``/``suptitle`` keywords for the problem's own title: the user's text, drawn as written (never
#: read as mathtext, where an unbalanced ``$`` fails), in the size of a figure's main title.
PROBLEM_TITLE: dict[str, Any] = {"fontsize": 10, "parse_math": False}


def drawn(drawers: Mapping[str, FigureDrawer]) -> dict[str, Figure]:
    """Every figure of ``drawers`` drawn, by file stem."""
    return {stem: draw() for stem, draw in drawers.items()}

"""Conventions every figure of the package follows, kept in one place so the figures look alike."""
from __future__ import annotations

from typing import Any

#: ``Axes.legend`` keywords that put the legend beside the axes, off the data (constrained layout makes room).
LEGEND_BESIDE: dict[str, Any] = {"loc": "upper left", "bbox_to_anchor": (1.02, 1), "borderaxespad": 0}
#: ``set_title``/``suptitle`` keywords for the problem's own title: the user's text, drawn as written (never
#: read as mathtext, where an unbalanced ``$`` fails), in the size of a figure's main title.
PROBLEM_TITLE: dict[str, Any] = {"fontsize": 10, "parse_math": False}

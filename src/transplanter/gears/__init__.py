"""Pairs of non-circular gears: pitch-curve families, closure, curvature, rack and shaper
teeth, drawings.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``GearProblem`` (mm, radians); ``synthesize(problem)`` -> ``GearResult`` (``to_json()``);
``draw_figures(result)`` -> matplotlib Figures by file stem; ``write_drawings(result, folder)``
-> CSV, SVG and DXF files.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["GearProblem", "GearResult", "draw_figures", "load_problem", "parse_problem", "synthesize",
           "write_drawings"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "draw_figures": "figures",
    "write_drawings": "drawings",
    "GearProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "GearResult": "result",
    "synthesize": "synthesis",
})

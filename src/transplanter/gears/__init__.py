"""Pairs of non-circular gears: pitch-curve families, closure, curvature, rack and shaper
teeth, drawings.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``GearProblem``; ``synthesize(problem)`` -> ``GearResult``; ``write_drawings``.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["GearProblem", "GearResult", "load_problem", "parse_problem", "synthesize", "write_drawings"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "write_drawings": "drawings",
    "GearProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "GearResult": "synthesis",
    "synthesize": "synthesis",
})

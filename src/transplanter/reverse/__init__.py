"""Reverse design of a planetary non-circular gear train from a closed path of the arm tip
(the rice-transplanter, reverse-gear-design and cusp-pitch-curve papers): inverse kinematics,
the monotonicity criterion, gears, round trip.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``ReverseProblem`` (mm); ``synthesize(problem)`` -> ``ReverseResult`` (``to_json()``);
``draw_figures(result)`` -> matplotlib Figures by file stem.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["ReverseProblem", "ReverseResult", "draw_figures", "load_problem", "parse_problem", "synthesize"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "draw_figures": "figures",
    "ReverseProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "ReverseResult": "result",
    "synthesize": "synthesis",
})

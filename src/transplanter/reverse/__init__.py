"""Reverse design of a planetary non-circular gear train from a closed path of the arm tip
(the rice-transplanter, reverse-gear-design and cusp-pitch-curve papers): inverse kinematics,
the monotonicity criterion, gears, round trip.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``ReverseProblem`` (mm); ``synthesize(problem)`` -> ``ReverseResult`` (``to_json()``);
``draw_figures(result)`` -> matplotlib Figures by file stem; ``load_design`` + ``evaluate_design`` -> the
train of a given design (the arm and train of a run's design.toml).
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["ReverseDesign", "ReverseProblem", "ReverseResult", "draw_figures", "evaluate_design", "load_design",
           "load_problem", "parse_problem", "synthesize"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "ReverseDesign": "design_toml",
    "evaluate_design": "design_toml",
    "load_design": "design_toml",
    "draw_figures": "figures",
    "ReverseProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "ReverseResult": "result",
    "synthesize": "synthesis",
})

"""Reverse design of a planetary non-circular gear train from a closed path of the arm tip
(seeds 002-004): inverse kinematics, the monotonicity criterion, gears, round trip.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``ReverseProblem``; ``synthesize(problem)`` -> ``ReverseResult``.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["ReverseProblem", "ReverseResult", "load_problem", "parse_problem", "synthesize"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "ReverseProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "ReverseResult": "synthesis",
    "synthesize": "synthesis",
})

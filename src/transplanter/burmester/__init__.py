"""RR dyads that guide a body through three or more poses (Burmester theory).

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``DyadProblem``; ``synthesize(problem)`` -> ``Synthesis``.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["DyadProblem", "Synthesis", "load_problem", "parse_problem", "synthesize"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "load_problem": "problem",
    "parse_problem": "problem",
    "DyadProblem": "synthesis",
    "Synthesis": "synthesis",
    "synthesize": "synthesis",
})

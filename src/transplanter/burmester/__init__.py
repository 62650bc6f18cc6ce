"""RR dyads that guide a body through three or more poses (Burmester theory).

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``DyadProblem`` (mm, radians); ``synthesize(problem)`` -> ``Synthesis`` (``to_json()``);
``draw_figures(result)`` -> matplotlib Figures by file stem; ``nearest_center(result, point)`` ->
``NearestCenter``, the true nearest point of a four-pose center-point curve and its dyad.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["DyadProblem", "NearestCenter", "Synthesis", "draw_figures", "load_problem", "nearest_center",
           "parse_problem", "synthesize"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "draw_figures": "figures",
    "DyadProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "NearestCenter": "nearest",
    "nearest_center": "nearest",
    "Synthesis": "result",
    "synthesize": "synthesis",
})

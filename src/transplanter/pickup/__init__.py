"""The seedling pick-up mechanism of the cusp-pitch-curve paper (section 6, eq 15), forward:
a bent carrier (L1, L2, delta0) carrying two non-circular gear stages (any gear family, composite
included) and the picking arm (S, alpha0); its tip path, picking and pushing angles, tip speed.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``PickupProblem``; ``synthesize(problem)`` -> ``PickupResult`` (``to_json()``);
``draw_figures(result)`` -> matplotlib Figures by file stem; ``write_animation(result, folder)``.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["PickupProblem", "PickupResult", "draw_figures", "load_problem", "parse_problem", "synthesize",
           "write_animation"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "draw_figures": "figures",
    "write_animation": "animation",
    "PickupProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "PickupResult": "result",
    "synthesize": "synthesis",
})

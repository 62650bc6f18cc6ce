"""The five-bar seedling pushing mechanism of Wang et al. 2025 with its planetary gear train.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``FiveBarProblem`` (mm, radians); ``synthesize(problem, pick=None, progress=None)`` -> ``FiveBarResult``
(region, every candidate refined and ranked, the picked one's whole-tooth gears cut and mesh-checked,
verification; ``to_json()``); ``draw_figures(result)`` -> matplotlib Figures by file
stem; ``write_files(result, folder, animation=True)`` -> the drawings, tables and animation;
``load_design`` + ``evaluate_design`` -> ``DesignEvaluation`` for a given (published) design. Both results
are ``CommandResult``s (passed, failures, to_json, to_markdown, draw_figures, write_files).
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["DesignEvaluation", "FiveBarProblem", "FiveBarResult", "GivenDesign", "draw_figures", "evaluate_design",
           "load_design", "load_problem", "parse_problem", "synthesize", "write_files"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "DesignEvaluation": "evaluation",
    "GivenDesign": "evaluation",
    "evaluate_design": "evaluation",
    "load_design": "evaluation",
    "draw_figures": "figures",
    "FiveBarProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "FiveBarResult": "result",
    "synthesize": "synthesis",
    "write_files": "output_files",
})

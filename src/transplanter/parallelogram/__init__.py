"""The onion transplanter of the onion-transplanter paper: a parallelogram planting mechanism driven by a pair of
denatured Pascal limacon gears, designed by NSGA-II and polished by an NLP.

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) ->
``ParallelogramProblem`` (mm, radians); ``load_design`` / ``parse_design`` -> ``DesignFile``;
``evaluate_design(problem, design)`` -> ``DesignReport`` (``to_json()``);
``draw_design_figures(problem, design)`` -> matplotlib Figures by file stem; ``synthesize(problem)``
-> ``ParallelogramResult`` (NSGA-II, the knee evaluated again, its gear pair; ``to_json()``);
``draw_figures(result)`` -> Figures by file stem; ``write_tables(result, folder)`` -> CSV files;
``write_files(result, folder, animation=True)`` -> the tables, gear drawings and animation. Both results are
``CommandResult``s (passed, failures, to_json, to_markdown, draw_figures, write_files).
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["DesignFile", "DesignReport", "ParallelogramProblem", "ParallelogramResult", "draw_design_figures",
           "draw_figures", "evaluate_design", "load_design", "load_problem", "parse_design", "parse_problem",
           "synthesize", "write_files", "write_tables"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "DesignFile": "evaluation",
    "load_design": "evaluation",
    "parse_design": "evaluation",
    "ParallelogramProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "DesignReport": "result",
    "ParallelogramResult": "result",
    "evaluate_design": "synthesis",
    "synthesize": "synthesis",
    "draw_design_figures": "figures",
    "draw_figures": "figures",
    "write_tables": "tables",
    "write_files": "output_files",
})

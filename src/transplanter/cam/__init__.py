"""Disc cams with a roller follower, translating (with offset) or oscillating, or a flat-faced
follower: motion programs of rise, dwell and return segments (harmonic, cycloidal, 3-4-5
polynomial, modified trapezoid), the pitch curve and profile, pressure angle, curvature, undercut
and interference checks, the smallest base circle for a pressure-angle limit, drawings; and the
seedling-support rocker-slider of Wang et al. 2025 (eq 14-15, Table 5).

Public API: ``load_problem`` / ``parse_problem`` (TOML file or dict, mm and degrees) -> ``CamProblem``
(mm, radians); ``synthesize(problem)`` -> ``CamResult`` (``to_json()``); ``draw_figures(result)`` ->
matplotlib Figures by file stem; ``write_drawings(result, folder)`` -> CSV, DXF and SVG files;
``load_design`` + ``evaluate_design`` -> the problem's cam on a given base circle (a run's design.toml).
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["CamDesign", "CamProblem", "CamResult", "draw_figures", "evaluate_design", "load_design", "load_problem",
           "parse_problem", "synthesize", "write_drawings"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "CamDesign": "design_toml",
    "evaluate_design": "design_toml",
    "load_design": "design_toml",
    "draw_figures": "figures",
    "write_drawings": "drawings",
    "CamProblem": "problem",
    "load_problem": "problem",
    "parse_problem": "problem",
    "CamResult": "result",
    "synthesize": "synthesis",
})

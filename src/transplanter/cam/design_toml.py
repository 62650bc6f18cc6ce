"""The design of a cam run in a file: [cam] base_radius_mm (and bore_radius_mm when the problem gives one) and the
disc's thickness_mm, the report's names. ``write_design`` writes a run's as design.toml; ``load_design`` reads one;
``evaluate_design`` makes the problem's cam on that base circle (design mode off), which reproduces the run that
wrote it."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

from transplanter.api_arguments import require_problem
from transplanter.cam.problem import CamProblem
from transplanter.cam.result import CamResult
from transplanter.cam.solid_files import disc_thickness
from transplanter.cam.synthesis import synthesize
from transplanter.design_file import read_design_file, write_design_file
from transplanter.errors import ProblemError
from transplanter.solids.sizes import SolidSizes
from transplanter.toml_fields import shown


@dataclass(frozen=True)
class CamDesign:
    """A cam's design: its base radius, when given its bore radius, and its disc's thickness (mm); the design
    file."""

    base_radius: float
    bore_radius: float | None
    solid_sizes: SolidSizes
    source: str


def write_design(result: CamResult, folder: str | Path) -> Path:
    """``folder/design.toml`` of ``result``; the path written."""
    problem = result.problem
    bore = {} if problem.bore_radius is None else {"bore_radius_mm": problem.bore_radius}
    return write_design_file(
        folder, "The cam made by transplanter cam",
        f"Made for {problem.title or problem.source}. Make it again with: transplanter cam {problem.source} "
        "--design design.toml", {"cam": {"base_radius_mm": result.base_radius, **bore,
                                         "thickness_mm": disc_thickness(result)}})


def load_design(path: str | Path) -> CamDesign:
    """Read a design file (TOML, mm): [cam] with base_radius_mm and optionally bore_radius_mm and thickness_mm. A bad
    field raises ProblemError (``read_design_file``)."""
    _, table, read = read_design_file(path, {"cam"}, "cam", {"base_radius_mm", "bore_radius_mm", "thickness_mm"})
    bore = read.length(table, "bore_radius_mm", "cam") if "bore_radius_mm" in table else None
    thickness = read.length(table, "thickness_mm", "cam") if "thickness_mm" in table else None
    return CamDesign(read.length(table, "base_radius_mm", "cam"), bore, SolidSizes(thickness_mm=thickness), str(path))


def evaluate_design(problem: CamProblem, design: CamDesign) -> CamResult:
    """The problem's cam on ``design``'s base circle, with its bore and disc thickness where it gives them
    (``synthesize``)."""
    require_problem(problem, CamProblem, "cam")
    if not isinstance(design, CamDesign):
        raise ProblemError(f"design = {shown(design)!r}: expected a CamDesign (from "
                           "transplanter.cam.load_design(path))")
    bore = problem.bore_radius if design.bore_radius is None else design.bore_radius
    sizes = problem.solid_sizes if design.solid_sizes.thickness_mm is None else design.solid_sizes
    return synthesize(dataclasses.replace(problem, base_radius=design.base_radius, max_base_radius=None,
                                          bore_radius=bore, solid_sizes=sizes))

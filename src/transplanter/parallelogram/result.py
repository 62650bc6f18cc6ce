"""Results of the onion-transplanter command, and the checks they pass."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from transplanter.command_result import CommandResult
from transplanter.gears.result import GearResult
from transplanter.parallelogram.evaluation import DesignFile, Evaluation
from transplanter.parallelogram.problem import ParallelogramProblem
from transplanter.parallelogram.search import SearchResult
from transplanter.tolerance import ToleranceAnalysis, ToleranceModel

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer


@dataclass(frozen=True)
class DesignReport(CommandResult):
    """A given design evaluated (``--design``): every reading of its gear and conventions, the
    gear pair through the gear library, the closed curve under the file's conventions, and how precise the
    built design will be (``tolerance``, None with ``tolerance=False``)."""

    problem: ParallelogramProblem
    given: DesignFile
    evaluations: list[Evaluation]
    closed: Evaluation
    gear: GearResult
    timings_s: dict = field(default_factory=dict)
    failures: tuple[str, ...] = ()
    tolerance: ToleranceAnalysis | None = None

    @property
    def source(self) -> str:
        """The problem file (the design is judged against its requirements)."""
        return self.problem.source

    def tolerance_model(self) -> ToleranceModel:
        """The given design, its gears at their closing centre distance, as a function of its manufactured
        dimensions (``parallelogram.tolerance_model``)."""
        from transplanter.parallelogram.tolerance_model import tolerance_model

        return tolerance_model(self.problem, self.given.design, self.gear.design.center_distance)

    def to_json(self) -> dict[str, Any]:
        from transplanter.parallelogram.report import design_report_json

        return design_report_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.parallelogram.report import evaluation_markdown

        return evaluation_markdown(self, files)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        """The design's trajectory, velocity and acceleration (``design_figure_drawers``), and with a tolerance
        analysis its figures."""
        from transplanter.parallelogram.figures import design_figure_drawers

        drawers = design_figure_drawers(self.problem, self.given.design)
        return {**drawers, **self.tolerance.figure_drawers()} if self.tolerance is not None else drawers


def objective_values(problem: ParallelogramProblem, evaluation: Evaluation) -> np.ndarray:
    """f1, f2, f3 of an evaluation (mm/s, mm, mm)."""
    return np.array([abs(evaluation.vx_release), abs(evaluation.depth - problem.depth_target),
                     abs(evaluation.vertical_range - problem.vertical_range_target)])


@dataclass(frozen=True)
class Polished:
    """The NLP polish of the chosen design: variables (mm, rad; None when IPOPT failed), their
    independent evaluation, whether they dominate the chosen design, IPOPT's status."""

    variables: dict | None
    evaluation: Evaluation | None
    dominates_start: bool
    status: str
    iterations: int
    solve_seconds: float

    def failures(self, problem: ParallelogramProblem) -> tuple[str, ...]:
        """The polished design must exist, meet Vx = 0 and H = target on the fine grid (to 1e-6 of the
        machine speed and of the target) and dominate its start."""
        if self.variables is None or self.evaluation is None:         # None both when IPOPT failed
            return (f"NLP polish failed (IPOPT status {self.status})",)
        e, out = self.evaluation, []
        if abs(e.vx_release) > 1e-6 * problem.forward_speed:
            out.append(f"polished Vx(t_E) = {e.vx_release:.3g} mm/s on the fine grid, not 0")
        if abs(e.depth - problem.depth_target) > 1e-6 * problem.depth_target:
            out.append(f"polished depth {e.depth:.6f} mm on the fine grid, not {problem.depth_target:g}")
        if not self.dominates_start:
            out.append("the polished design does not dominate the NSGA-II design it started from")
        return tuple(out)


@dataclass(frozen=True)
class ParallelogramResult(CommandResult):
    """A designed onion transplanter: the Pareto designs of NSGA-II, the picked one evaluated again
    independently on a finer grid, its gear pair, and the published optimum for comparison.

    Attributes
    ----------
    problem : ParallelogramProblem
    search : SearchResult
        Pareto designs ranked from the knee (rank 1).
    pick : int
        Rank of the chosen design.
    chosen : dict
        Its eight variables (mm, rad).
    evaluation : Evaluation
        Its independent evaluation (8192 samples per turn).
    gear : GearResult
        Its gear pair through the gear library.
    start : Evaluation
        The file's [design] (start values) evaluated the same way.
    published : list of Evaluation
        The file's [design] under every reading of its gear and conventions (``evaluate_published``).
    failures : tuple of str
        Why the result fails its checks (empty when it passes).
    tolerance : ToleranceAnalysis or None
        How precise the built final design will be (``tolerance.analyse``), else None (``tolerance=False``).
    """

    problem: ParallelogramProblem
    search: SearchResult
    pick: int
    chosen: dict
    evaluation: Evaluation
    gear: GearResult
    start: Evaluation
    timings_s: dict
    failures: tuple[str, ...] = ()
    polished: Polished | None = None
    published: list[Evaluation] = field(default_factory=list)
    tolerance: ToleranceAnalysis | None = None

    @property
    def final(self) -> dict:
        """The design the gears, drawings and figures are made for: the polished one, else the chosen one."""
        return self.polished.variables if self.polished is not None and self.polished.variables else self.chosen

    @property
    def final_evaluation(self) -> Evaluation:
        polished = self.polished
        if polished is not None and polished.variables and polished.evaluation is not None:
            return polished.evaluation
        return self.evaluation

    @property
    def source(self) -> str:
        return self.problem.source

    def tolerance_model(self) -> ToleranceModel:
        """The final design, its gears built to whole teeth, as a function of its manufactured dimensions
        (``parallelogram.tolerance_model``)."""
        from transplanter.parallelogram.tolerance_model import tolerance_model

        return tolerance_model(self.problem, self.final, self.gear.design.center_distance)

    def to_json(self) -> dict[str, Any]:
        from transplanter.parallelogram.report import parallelogram_result_json

        return parallelogram_result_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.parallelogram.report import to_markdown

        return to_markdown(self, files)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.parallelogram.figures import figure_drawers

        return figure_drawers(self)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """``parallelogram.write_files``: the tables, the gear drawings, their STEP solids unless ``solids`` is False
        and, unless ``animation`` is False, the animation."""
        from transplanter.parallelogram.output_files import write_files

        return write_files(self, folder, animation=animation, solids=solids)

"""What a dyad synthesis found, and whether it found any."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from transplanter.burmester.problem import DyadProblem
from transplanter.command_result import CommandResult
from transplanter.geometry.curve_trace import CurveTrace
from transplanter.geometry.dyad import Dyad

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer


@dataclass(frozen=True)
class Synthesis(CommandResult):
    """RR dyads found for a ``DyadProblem``.

    Attributes
    ----------
    problem : DyadProblem
        The problem solved (mm, radians).
    method : str
        How the dyads were found (follows the pose count).
    dyads : list of Dyad
        Fixed pivot ``center`` and moving pivot ``circle`` in pose 1 (mm), link length (mm) and
        residuals from forward kinematics (mm).
    radius_mm : float
        Search radius about the poses' centroid (mm).
    center_curve, circle_curve : CurveTrace or None
        Center-point and circle-point curves in world mm (four poses only).
    circle_curve_dyads : list of Dyad
        Dyads traced along the circle-point curve (four poses only).
    rms_mm : list of float
        RMS length error of each least-squares dyad (mm; six poses or more).
    """

    problem: DyadProblem
    method: str
    dyads: list[Dyad]
    radius_mm: float
    center_curve: CurveTrace | None = None
    circle_curve: CurveTrace | None = None
    circle_curve_dyads: list[Dyad] = field(default_factory=list)
    rms_mm: list[float] = field(default_factory=list)

    @property
    def source(self) -> str:
        return self.problem.source

    @property
    def failures(self) -> list[str]:
        """Why the synthesis has no result: no dyad found (empty when it found one)."""
        if self.dyads or self.circle_curve_dyads:
            return []
        return [f"no dyad found within search.radius_mm = {self.radius_mm:.6g} mm of the poses' centroid: enlarge "
                "search.radius_mm, or check that the poses belong to one rigid body's motion"]

    def to_json(self) -> dict[str, Any]:
        from transplanter.burmester.report import synthesis_json

        return synthesis_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.burmester.report import to_markdown

        return to_markdown(self, files)

    def to_text(self) -> str:
        from transplanter.burmester.report import to_text

        return to_text(self)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.burmester.figures import figure_drawers

        return figure_drawers(self)

"""A designed cam, and the checks it passes."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from transplanter import progress
from transplanter.cam.checks import CamChecks, Extreme
from transplanter.cam.kinematics import CamGeometry
from transplanter.cam.problem import CamProblem
from transplanter.command_result import CommandResult

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer


@dataclass(frozen=True)
class CamResult(CommandResult):
    """A cam for a ``CamProblem``.

    Attributes
    ----------
    problem : CamProblem
    geometry : CamGeometry
        Motion, pitch curve, profile, pressure angle and curvature at ``problem.samples`` cam angles.
    checks : CamChecks
    designed : bool
        The base radius was found by design mode (the smallest meeting the limits).
    cams_evaluated : int
        Design mode: base radii tried.
    timings_s : dict
    """

    problem: CamProblem
    geometry: CamGeometry
    checks: CamChecks
    designed: bool
    cams_evaluated: int
    timings_s: dict

    @property
    def source(self) -> str:
        return self.problem.source

    @property
    def base_radius(self) -> float:
        return self.geometry.base_radius

    @property
    def nearest_profile(self) -> Extreme:
        """The profile's smallest distance from the cam centre (mm) on the samples, and where."""
        distance = np.linalg.norm(self.geometry.profile, axis=1)
        k = int(np.argmin(distance))
        return Extreme(float(distance[k]), float(self.geometry.angle[k]))

    @property
    def failures(self) -> list[str]:
        """The checks' failures, and a given bore that reaches the profile (design mode sizes the cam by the
        checks alone: a bore is the designer's to fit)."""
        bore, nearest = self.problem.bore_radius, self.nearest_profile
        if bore is None or bore < nearest.value:
            return self.checks.failures
        return self.checks.failures + [f"cam.bore_radius = {bore:g} mm reaches the profile, which comes within "
                                       f"{nearest.value:.4f} mm of the centre at cam angle "
                                       f"{np.degrees(nearest.angle):.2f} deg"]

    def to_json(self) -> dict[str, Any]:
        from transplanter.cam.report import cam_result_json

        return cam_result_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.cam.report import to_markdown

        return to_markdown(self, files)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.cam.figures import figure_drawers

        return figure_drawers(self)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """The profile as CSV, DXF and SVG (``cam.write_drawings``), design.toml (``design_toml``) and, unless
        ``solids`` is False, the disc's STEP solid with the extra transplanter[cad] (``cam.solid_files``)."""
        from transplanter.cam.design_toml import write_design
        from transplanter.cam.drawings import write_drawings
        from transplanter.cam.solid_files import write_solids

        with progress.step("drawings"):
            written = [*write_drawings(self, folder), write_design(self, folder)]
        if not solids:
            return written
        with progress.step("solids"):
            return written + write_solids(self, Path(folder))

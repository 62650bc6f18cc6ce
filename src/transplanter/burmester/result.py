"""What a dyad synthesis found, and its JSON (the content of report.json)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from transplanter.burmester.problem import DyadProblem
from transplanter.geometry.curve_trace import CurveTrace
from transplanter.geometry.dyad import Dyad


def _dyad_json(dyad: Dyad) -> dict:
    return {"center": dyad.center.tolist(), "circle": dyad.circle.tolist(), "length": dyad.length,
            "max_residual": dyad.max_residual, "max_residual_mm": dyad.max_residual_mm,
            "residuals_mm": dyad.residuals_mm.tolist()}


@dataclass(frozen=True)
class Synthesis:
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
    def passed(self) -> bool:
        """Whether any dyad was found."""
        return bool(self.dyads or self.circle_curve_dyads)

    @property
    def failures(self) -> list[str]:
        """Why the synthesis has no result (empty when it passed)."""
        if self.passed:
            return []
        return [f"no dyad found within search.radius_mm = {self.radius_mm:.6g} mm of the poses' centroid: enlarge "
                "search.radius_mm, or check that the poses belong to one rigid body's motion"]

    def to_json(self) -> dict:
        """The report as plain JSON types (lengths in mm, angles in degrees): the content of report.json."""
        problem = self.problem
        dyads = self.dyads + self.circle_curve_dyads
        out = {
            "source": problem.source,
            "title": problem.title,
            "method": self.method,
            "pose_count": len(problem.poses),
            "poses": [{"label": label, "x": p[0], "y": p[1], "angle_deg": float(np.degrees(p[2]))}
                      for label, p in zip(problem.labels or [""] * len(problem.poses), problem.poses.tolist())],
            "relative": None if problem.link is None else {
                "pivot": problem.link.pivot.tolist(), "phases_deg": np.degrees(problem.link.phases).tolist()},
            "pose_scale_mm": dyads[0].scale if dyads else None,
            "radius_mm": self.radius_mm,
            "max_residual": max((d.max_residual for d in dyads), default=None),
            "dyads": [_dyad_json(d) for d in self.dyads],
        }
        if self.center_curve is not None:
            out["circle_curve_dyads"] = [_dyad_json(d) for d in self.circle_curve_dyads]
        if self.rms_mm:
            out["rms_mm"] = self.rms_mm
        return out

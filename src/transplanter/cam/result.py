"""A designed cam, and its JSON (the content of report.json)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.cam.checks import CamChecks, Extreme, Stretch
from transplanter.cam.kinematics import CamGeometry
from transplanter.cam.problem import CamProblem


def _extreme(extreme: Extreme | None, scale=float):
    return None if extreme is None else float(scale(extreme.value))


def _at(extreme: Extreme | None):
    return None if extreme is None else float(np.degrees(extreme.angle))


def _stretch(stretch: Stretch) -> dict:
    return {"from_deg": float(np.degrees(stretch.start)), "to_deg": float(np.degrees(stretch.end)),
            "worst_mm": stretch.worst}


def _finite(value):
    return None if value is None or not np.isfinite(value) else float(value)


@dataclass(frozen=True)
class CamResult:
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

    @property
    def passed(self) -> bool:
        return not self.failures

    def to_json(self) -> dict:
        """The report as plain JSON types (mm and degrees; a swing in degrees): the content of report.json."""
        problem, checks, follower = self.problem, self.checks, self.problem.follower
        swing, flat = problem.oscillating, follower.kind == "flat_faced"
        unit = np.degrees if swing else float
        jumps = [{"at_deg": round(float(np.degrees(j.angle)), 9),
                  "between": [self._segment_name(j.before), self._segment_name(j.after)],
                  "size": float(unit(j.size)), "unit": "deg/rad^2" if swing else "mm/rad^2"}
                 for j in checks.acceleration_jumps]
        return {
            "source": problem.source, "title": problem.title,
            "follower": {"kind": follower.kind, "roller_radius_mm": follower.roller_radius,
                         **({"pivot_mm": follower.pivot.tolist(), "arm_length_mm": follower.arm_length,
                             "roller_side": "pulled" if follower.pulled else "pushed"} if swing
                            else {"face_offset_range_mm": [float(self.geometry.center[:, 0].min()),
                                                           float(self.geometry.center[:, 0].max())]} if flat
                            else {"offset_mm": follower.offset})},
            "direction": "counterclockwise" if problem.direction > 0 else "clockwise",
            "base_radius_mm": self.base_radius,
            "bore_radius_mm": problem.bore_radius,
            "nearest_profile_mm": {"distance": self.nearest_profile.value, "at_deg": _at(self.nearest_profile)},
            "designed_base_radius": self.designed,
            "cams_evaluated": self.cams_evaluated,
            "segments": [{"kind": s.kind, "angle_deg": round(float(np.degrees(s.angle)), 9), "law": s.law,
                          ("swing_deg" if swing else "lift_mm"): round(float(unit(abs(s.lift))), 9)} for s in problem.segments],
            "laws": sorted({s.law for s in problem.segments if s.law}),
            "max_pressure_angle_deg": {"rise": _extreme(checks.pressure["rise"], np.degrees),
                                       "return": _extreme(checks.pressure["return"], np.degrees),
                                       "at_deg": {"rise": _at(checks.pressure["rise"]),
                                                  "return": _at(checks.pressure["return"])},
                                       "limit": round(float(np.degrees(problem.pressure_limit)), 9)},
            "min_curvature_radius_mm": {"pitch": _extreme(checks.min_pitch_radius),
                                        "profile": _extreme(checks.min_profile_radius),
                                        "concave_profile": _finite(_extreme(checks.min_concave_profile_radius)),
                                        "profile_limit": problem.profile_radius_limit,
                                        "at_deg": {"pitch": _at(checks.min_pitch_radius),
                                                   "profile": _at(checks.min_profile_radius),
                                                   "concave_profile": _at(checks.min_concave_profile_radius)}},
            "undercut": bool(checks.undercut),
            "undercut_stretches": [_stretch(s) for s in checks.undercut],
            "roller_interference": [_stretch(s) for s in checks.interference],
            "acceleration_jumps": jumps,
            "laws_with_acceleration_jumps": sorted({self.problem.segments[k].law for j in checks.acceleration_jumps
                                                    for k in (j.before, j.after) if self.problem.segments[k].law}),
            "displacement_range": [float(unit(self.geometry.motion[0].min())), float(unit(self.geometry.motion[0].max()))],
            "samples": int(self.geometry.angle.size),
            "timings_s": self.timings_s,
        }

    def _segment_name(self, index: int) -> str:
        segment = self.problem.segments[index]
        return f"{index + 1}: {segment.kind}" + (f" ({segment.law})" if segment.law else "")

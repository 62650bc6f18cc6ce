"""A designed gear pair, and its JSON (the content of report.json)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.gears.composite_curve import CompositeCurve, cusps
from transplanter.gears.composite_teeth import CompositeTeeth, composite_teeth_json
from transplanter.gears.pair import GearPairDesign
from transplanter.gears.problem import GearProblem
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.gears.teeth import PairTeeth


@dataclass(frozen=True)
class ToothCounts:
    """Nearest whole tooth counts with equal teeth per lobe, and what makes them exact.

    Attributes
    ----------
    module : float
        The module asked for (mm).
    fractional : (float, float)
        Teeth that fit each perimeter at that module.
    counts : (int, int)
        Nearest whole counts, equal per lobe.
    exact_module : float
        Module that makes ``counts`` exact at this size (mm).
    scale_for_module : float
        Scale of the curves that makes ``counts`` exact with ``module``.
    """

    module: float
    fractional: tuple[float, float]
    counts: tuple[int, int]
    exact_module: float
    scale_for_module: float


def _min_convex(rho, convexity):
    convex = convexity > 0
    return float(rho[convex].min()) if convex.any() else None


@dataclass(frozen=True)
class GearResult:
    """A pair of non-circular gears designed from a ``GearProblem``.

    Attributes
    ----------
    problem : GearProblem
        The problem solved.
    design : GearPairDesign
        Pitch curves (mm) sampled over the driver angle (rad), center distance (mm), closure
        error (rad), ratio i12, driven speed (rad/s) and acceleration (rad/s^2), curvature radii (mm).
    tooth_counts : ToothCounts or None
        When a module is given.
    teeth : PairTeeth or None
        Tooth outlines (mm) when teeth are given.
    ratio_correction : float or None
        Factor k that scaled a given ratio to close (Wang et al. 2025 eq 12).
    timings_s : dict
        Wall time of each stage (s).
    """

    problem: GearProblem
    design: GearPairDesign
    tooth_counts: ToothCounts | None
    teeth: PairTeeth | None
    ratio_correction: float | None
    timings_s: dict

    @property
    def failures(self) -> list[str]:
        """Checks the pair fails: tooth outlines that cross themselves (a cutter that cuts away teeth it
        made) cannot be made or drawn as given; composite teeth add their contact and mesh checks."""
        if self.teeth is None:
            return []
        composite = getattr(self.teeth, "failures", None)
        if composite is not None:          # composite teeth name their own crossings
            return list(composite)
        if not any(self.teeth.self_intersections):
            return []
        driver, driven = self.teeth.self_intersections
        return [f"tooth outlines cross themselves (driver {driver}, driven {driven} crossings): the cutter cuts "
                "away teeth it made, usually where a pitch curve bends sharper than the tooth; try fewer teeth "
                "(a larger pair.module), or pair.cutter = \"shaper\" for concave stretches"]

    @property
    def passed(self) -> bool:
        """Whether the pair passes its checks (``failures`` empty)."""
        return not self.failures

    def to_json(self) -> dict:
        """The report as plain JSON types (mm, rad, rad/s): the content of report.json."""
        d, problem = self.design, self.problem
        out = {
            "source": problem.source, "title": problem.title,
            "driver": {"family": d.driver.family, "parameters": problem.parameters, "scale": d.driver.scale},
            "center_distance": d.center_distance,
            "orders": list(d.orders),
            "closure_error": d.closure_error,
            "rolling_mismatch_mm": d.rolling_mismatch_mm,
            "ratio_range": [float(d.ratio.min()), float(d.ratio.max())],
            "perimeters": list(d.perimeters),
            "convex": [bool((c > 0).all()) for c in d.convexity],
            "min_curvature_radius": [_min_convex(r, c) for r, c in zip(d.curvature_radius, d.convexity)],
            "joints": d.joints,
            "cusps": cusps(d.driver, d.center_distance) if isinstance(d.driver, CompositeCurve) else None,
            "driver_speed_rad_s": d.driver_speed,
            "driven_speed_range_rad_s": [float(d.driven_speed.min()), float(d.driven_speed.max())],
            "driven_acceleration_range_rad_s2": [float(d.driven_acceleration.min()),
                                                 float(d.driven_acceleration.max())],
            "ratio_correction_factor": self.ratio_correction,
            "module": problem.module,
            "tooth_counts": None, "undercut": None, "contact_ratio_range": None, "self_intersections": None,
            "timings_s": self.timings_s,
        }
        if self.tooth_counts is not None:
            counts = self.tooth_counts
            limit = ADDENDUM * counts.module / np.sin(problem.pressure_angle) ** 2
            out["tooth_counts"] = {"fractional": list(counts.fractional), "nearest": list(counts.counts),
                                   "exact_module": counts.exact_module, "scale_for_module": counts.scale_for_module}
            out["undercut"] = [bool(v is not None and v < limit) for v in out["min_curvature_radius"]]
        if self.teeth is not None:
            out["cutter"] = self.teeth.cutter
            out["contact_ratio_range"] = None if self.teeth.contact_ratio is None else list(self.teeth.contact_ratio)
            out["self_intersections"] = list(self.teeth.self_intersections)
        if isinstance(self.teeth, CompositeTeeth):
            out.update(composite_teeth_json(self.teeth))
        return out

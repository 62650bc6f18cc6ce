"""A designed five-bar mechanism with its gear train, and its JSON (the content of report.json)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.alternatives import RANKING_RULE, ActiveBound, Alternative, Failure
from transplanter.fivebar.candidate import Candidate
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.nlp import BENDING_WEIGHT, DesignSolution
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import Region
from transplanter.fivebar.support import SupportDesign
from transplanter.fivebar.verification import Verification
from transplanter.trains.planetary import PlanetaryTrain, printed_correction
from transplanter.trains.toothed_train import ToothedTrain, TrainSize, toothed_train_json


def design_json(mech: FiveBar, pose1: np.ndarray) -> dict:
    """Named lengths (mm), hinge coordinates in pose 1 (mm) and angles in pose 1 (deg)."""
    e, f = mech.plate_points(pose1)
    a = mech.carrier_point(0.0)
    return {
        "carrier_length_OA": mech.carrier_length, "rod_length_AF": mech.rod_length,
        "plate_link_length_EF": mech.link_length, "receiving_plate_length_BE": mech.receiving_length,
        "push_plate_EP": mech.ep, "push_plate_FP": mech.fp, "frame_length_OB": float(np.hypot(*mech.hinge_b)),
        "hinge_O": [0.0, 0.0], "hinge_B": mech.hinge_b.tolist(), "hinge_A": a.tolist(), "hinge_E": e.tolist(),
        "hinge_F": f.tolist(), "carrier_angle_deg": float(np.degrees(mech.carrier_angle)),
        "rod_angle_deg": float(np.degrees(np.arctan2(*(f - a)[::-1]))), "assembly_branch": mech.branch,
    }


def _stage_json(stage, name: str) -> dict:
    return {"pair": name, "center_distance": stage.center_distance, "closure_error_rad": stage.closure_error,
            "rolling_mismatch_mm": stage.rolling_mismatch_mm,
            "driver_radius_range": [float(stage.radius[0].min()), float(stage.radius[0].max())],
            "driven_radius_range": [float(stage.radius[1].min()), float(stage.radius[1].max())],
            "driver_convex": bool(np.all(stage.convexity[0] > 0)), "driven_convex": bool(np.all(stage.convexity[1] > 0)),
            "perimeters_mm": list(stage.perimeters)}


def bounds_json(bounds: tuple[ActiveBound, ...]) -> list[dict]:
    """Active bounds as ``{"bound", "side", "limit", "value"}``."""
    return [{"bound": b.name, "side": b.side, "limit": b.limit, "value": b.value} for b in bounds]


def alternative_json(alternative: Alternative, rank: int, pose1: np.ndarray) -> dict:
    """One ranked alternative (mm, degrees); ``start_candidates`` number the region's feasible
    candidates from 1 in the region's order."""
    design = alternative.design
    return {"rank": rank, "design": design_json(design.mech, pose1),
            "transmission_angle_min_deg": float(np.degrees(alternative.transmission_angle)),
            "transmission_angle_min_at_deg": float(np.degrees(alternative.transmission_turn)),
            "closure_angle_min_deg": float(np.degrees(alternative.closure_angle)),
            "closure_angle_min_at_deg": float(np.degrees(alternative.closure_turn)),
            "min_closure_margin": alternative.min_closure_margin, "ratio_range": list(alternative.ratio_range),
            "return_point_errors_mm": alternative.return_misses_mm.tolist(),
            "active_bounds": bounds_json(alternative.active_bounds),
            "start_candidates": [k + 1 for k in alternative.starts], "restroke": alternative.restroke or None,
            "gears": (alternative.gears.to_json() if isinstance(alternative.gears, TrainSize)
                      else {"none": alternative.gears}),
            "nlp": {"status": design.status, "iterations": design.iterations, "objective": design.objective}}


@dataclass(frozen=True)
class FiveBarResult:
    """A five-bar mechanism designed for a ``FiveBarProblem``, with its planetary gear train.

    Attributes
    ----------
    problem : FiveBarProblem
        The problem solved (mm, radians).
    region : Region
        The solution region: traced B-E and A-F dyads and the five-bars they pair into.
    start : Candidate
        The region candidate the picked design was refined from (the first of its starts).
    design : DesignSolution
        The picked refined mechanism (mm, rad), the relative angle of rod I as a B-spline of the
        carrier turn (rad), the return stroke, and the NLP's objective, iterations and status.
    toothed : ToothedTrain
        The four gears with whole teeth on the carrier: pitch curves (mm), counts, cutters, tooth
        outlines and the mesh check of each stage; ``train`` is its ``PlanetaryTrain``.
    verification : Verification
        The independent forward simulation: errors at the key poses (mm, deg) and return
        points (mm), trajectory of P over a turn (mm), closure margin, ratio range.
    timings_s : dict
        Wall time of each stage (s); ``nlp_per_candidate`` lists each refinement's.
    alternatives : tuple of Alternative
        Every distinct refined design, ranked (``fivebar.alternatives``); ``design`` is number ``picked``.
    failed : tuple of Failure
        The feasible candidates whose refinement failed, with the reason.
    picked : int
        Which alternative was built (1-based).
    support : SupportDesign or None
        The seedling support timed to the design (``[support]``), else None.
    """

    problem: FiveBarProblem
    region: Region
    start: Candidate
    design: DesignSolution
    toothed: ToothedTrain
    verification: Verification
    timings_s: dict
    alternatives: tuple[Alternative, ...]
    failed: tuple[Failure, ...]
    picked: int
    support: SupportDesign | None = None

    @property
    def train(self) -> PlanetaryTrain:
        """The pitch curves of the two gear stages and the correction factor k."""
        return self.toothed.train

    @property
    def failures(self) -> list[str]:
        """Every check of the built mechanism it fails: verification, the gears' mesh, then the support."""
        return [*self.verification.failures, *self.toothed.failures, *(self.support.failures if self.support else [])]

    @property
    def passed(self) -> bool:
        return not self.failures

    @property
    def chosen(self) -> Alternative:
        """The picked alternative."""
        return self.alternatives[self.picked - 1]

    def to_json(self) -> dict:
        """The report as plain JSON types (mm, degrees): the content of report.json."""
        problem, design, train, check = self.problem, self.design, self.train, self.verification
        toothed = toothed_train_json(self.toothed)
        relative = design.relative_angle
        k_printed, turn_printed = printed_correction(relative)
        region, chosen = self.region, self.chosen
        support = {"support": self.support.to_json()} if self.support else {}
        return {
            "source": problem.source, "title": problem.title,
            "key_pose_position_errors_mm": check.key_position_errors_mm.tolist(),
            "key_pose_angle_errors_deg": check.key_angle_errors_deg.tolist(),
            "return_point_errors_mm": check.return_point_errors_mm.tolist(),
            "return_tolerance_mm": problem.return_tolerance_mm,
            "min_discriminant": check.min_discriminant,
            "min_closure_margin": check.min_closure_margin,
            "required_closure_margin": problem.min_closure_margin,
            "relative_angle_monotonic": check.relative_angle_monotonic,
            "ratio_range": list(check.ratio_range),
            "transmission_angle_min_deg": float(np.degrees(chosen.transmission_angle)),
            "transmission_angle_min_at_deg": float(np.degrees(chosen.transmission_turn)),
            "closure_angle_min_deg": float(np.degrees(chosen.closure_angle)),
            "closure_angle_min_at_deg": float(np.degrees(chosen.closure_turn)),
            "active_bounds": bounds_json(chosen.active_bounds),
            "picked": self.picked, "ranking_rule": RANKING_RULE,
            "alternatives": [alternative_json(a, k + 1, problem.poses[0]) for k, a in enumerate(self.alternatives)],
            "failed": [{"candidate": f.start + 1, "reason": f.reason} for f in self.failed],
            "design": design_json(design.mech, problem.poses[0]),
            "relative_angle": {"rho1_deg": float(np.degrees(relative.rho1)),
                               "control_values_deg": np.degrees(relative.coefficients).tolist(),
                               "return_point_turns_deg": np.degrees(design.stroke.carrier_turns).tolist()},
            "gear_closure_errors": [train.stage_one.closure_error, train.stage_two.closure_error],
            "gears": toothed["gears"], "mesh_check": toothed["mesh_check"],
            "gear_train": {"correction_k": train.correction, "printed_eq12_k": k_printed,
                           "printed_eq12_intermediate_turn_deg": float(np.degrees(turn_printed)),
                           **{key: toothed[key] for key in ("layout", "module", "pressure_angle_deg",
                                                            "center_distances_mm", "teeth", "bend_angle_deg",
                                                            "shaft_mm")},
                           "stages": [_stage_json(train.stage_one, "sun -> first intermediate"),
                                      _stage_json(train.stage_two, "second intermediate -> planet")]},
            "roundtrip_max_error_mm": check.roundtrip_max_error_mm,
            "contact_gap_mm": check.contact_gap_mm,
            "region": {"receiving_dyads": len(region.receiving.fixed),
                       "receiving_kept": int(region.receiving.kept.sum()),
                       "carrier_dyads": len(region.carrier.fixed), "carrier_kept": int(region.carrier.kept.sum()),
                       "pairs": len(region.candidates), "feasible_pairs": len(region.feasible),
                       "removed_by": region.pair_defects,
                       "start_min_closure_margin": self.start.min_margin},
            "nlp": {"status": design.status, "iterations": design.iterations, "objective": design.objective,
                    "bending_weight": BENDING_WEIGHT, "curvature_floor": design.curvature_floor,
                    "convexity_note": design.convexity_note},
            **support,
            "timings_s": self.timings_s,
        }

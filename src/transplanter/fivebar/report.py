"""Five-bar results as JSON (machine) and Markdown (report file, terminal)."""
from __future__ import annotations

import numpy as np

from transplanter.fivebar.evaluation import DesignEvaluation
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.nlp import BENDING_WEIGHT
from transplanter.fivebar.synthesis import FiveBarResult
from transplanter.trains.planetary import printed_correction


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


def to_json(result: FiveBarResult) -> dict:
    problem, design, train, check = result.problem, result.design, result.train, result.verification
    relative = design.relative_angle
    k_printed, turn_printed = printed_correction(relative)
    return {
        "source": problem.source, "title": problem.title,
        "key_pose_position_errors_mm": check.key_position_errors_mm.tolist(),
        "key_pose_angle_errors_deg": check.key_angle_errors_deg.tolist(),
        "return_point_errors_mm": check.return_point_errors_mm.tolist(),
        "min_discriminant": check.min_discriminant,
        "min_closure_margin": check.min_closure_margin,
        "required_closure_margin": problem.min_closure_margin,
        "relative_angle_monotonic": check.relative_angle_monotonic,
        "ratio_range": list(check.ratio_range),
        "design": design_json(design.mech, problem.poses[0]),
        "relative_angle": {"rho1_deg": float(np.degrees(relative.rho1)),
                           "control_values_deg": np.degrees(relative.coefficients).tolist(),
                           "return_point_turns_deg": np.degrees(design.stroke.carrier_turns).tolist()},
        "gear_closure_errors": [train.stage_one.closure_error, train.stage_two.closure_error],
        "gears": {"correction_k": train.correction, "printed_eq12_k": k_printed,
                  "printed_eq12_intermediate_turn_deg": float(np.degrees(turn_printed)),
                  "stages": [_stage_json(train.stage_one, "sun -> first intermediate"),
                             _stage_json(train.stage_two, "second intermediate -> planet")]},
        "roundtrip_max_error_mm": check.roundtrip_max_error_mm,
        "contact_gap_mm": check.contact_gap_mm,
        "region": {"receiving_dyads": len(result.region.receiving.fixed),
                   "receiving_kept": int(result.region.receiving.kept.sum()),
                   "carrier_dyads": len(result.region.carrier.fixed), "carrier_kept": int(result.region.carrier.kept.sum()),
                   "pairs": len(result.region.candidates), "feasible_pairs": len(result.region.feasible),
                   "removed_by": result.region.pair_defects,
                   "start_min_closure_margin": result.start.min_margin},
        "nlp": {"status": design.status, "iterations": design.iterations, "objective": design.objective,
                "bending_weight": BENDING_WEIGHT},
        "timings_s": result.timings_s,
    }


def evaluation_json(evaluation: DesignEvaluation, pose1: np.ndarray) -> dict:
    candidate = evaluation.candidate
    return {
        "source": evaluation.design.source,
        "key_pose_position_errors_mm": evaluation.position_errors_mm.tolist(),
        "key_pose_angle_errors_deg": evaluation.angle_errors_deg.tolist(),
        "receiving_chain_errors_mm": evaluation.chain_errors_mm[0].tolist(),
        "carrier_chain_errors_mm": evaluation.chain_errors_mm[1].tolist(),
        "violations": candidate.defects,
        "min_closure_margin": candidate.min_margin,
        "relative_angle_monotonic": candidate.relative_angle is not None and "monotonic" not in " ".join(candidate.defects),
        "ratio_range": list(candidate.ratio_range),
        "assemblies_worst_position_error_mm": evaluation.alternatives,
        "design": design_json(evaluation.mech, pose1),
    }


def _row(label, values, digits=3):
    return f"| {label} | " + " | ".join(f"{v:.{digits}g}" if isinstance(v, float) else str(v) for v in values) + " |"


def to_markdown(report: dict, labels: tuple[str, ...], figures: list[str]) -> str:
    d = report["design"]
    lines = [f"# Five-bar seedling pushing mechanism: {report['title'] or report['source']}", "",
             "## Key poses (forward simulation: gears rolling, then the linkage)", "",
             "| | " + " | ".join(labels) + " |", "|---" * (len(labels) + 1) + "|",
             _row("P position error (mm)", report["key_pose_position_errors_mm"]),
             _row("plate angle error (deg)", report["key_pose_angle_errors_deg"]), "",
             f"Return points reached within {max(report['return_point_errors_mm']):.3g} mm (least squares). "
             f"Gear trajectory against the designed one: {report['roundtrip_max_error_mm']:.3g} mm at most; "
             f"pitch-curve contact gap {report['contact_gap_mm']:.3g} mm.", "",
             "## Design (pose 1)", "", "| quantity | value |", "|---|---|"]
    lines += [f"| {key} | {value if isinstance(value, (str, list)) else round(value, 4)} |" for key, value in d.items()]
    lines += ["", "## Whole turn", "",
              f"- smallest closure margin sin²(EBF): {report['min_closure_margin']:.5f} "
              f"(required {report['required_closure_margin']}); eq (10) discriminant ≥ {report['min_discriminant']:.4g} mm⁴",
              f"- relative angle strictly increasing: {report['relative_angle_monotonic']}; total ratio i0 in "
              f"[{report['ratio_range'][0]:.4f}, {report['ratio_range'][1]:.4f}]", ""]
    gears = report["gears"]
    lines += ["## Gears (eq 11-13)", "",
              f"Correction factor k = {gears['correction_k']:.6f}. Eq (12) as printed (integrating over the relative "
              f"angle) gives k = {gears['printed_eq12_k']:.6f}, with which the first intermediate gear turns "
              f"{gears['printed_eq12_intermediate_turn_deg']:.3f} deg per sun turn instead of 360.", "",
              "| pair | a (mm) | closure error (rad) | driver r (mm) | driven r (mm) | convex |", "|---|---|---|---|---|---|"]
    for stage in gears["stages"]:
        lines.append(f"| {stage['pair']} | {stage['center_distance']:.3f} | {stage['closure_error_rad']:.2g} | "
                     f"{stage['driver_radius_range'][0]:.3f}-{stage['driver_radius_range'][1]:.3f} | "
                     f"{stage['driven_radius_range'][0]:.3f}-{stage['driven_radius_range'][1]:.3f} | "
                     f"{stage['driver_convex']}/{stage['driven_convex']} |")
    region = report["region"]
    lines += ["", "## Solution region", "",
              f"{region['receiving_kept']} of {region['receiving_dyads']} B-E dyads and {region['carrier_kept']} of "
              f"{region['carrier_dyads']} A-F dyads within ranges; {region['feasible_pairs']} of {region['pairs']} "
              f"five-bars feasible (removed by: {region['removed_by']}).", "",
              f"NLP: {report['nlp']['status']} in {report['nlp']['iterations']} iterations.", ""]
    lines += [f"![{name}]({name})" for name in figures]
    return "\n".join(lines) + "\n"


def evaluation_markdown(report: dict, labels: tuple[str, ...]) -> str:
    lines = [f"# Given design {report['source']}", "", "| | " + " | ".join(labels) + " |",
             "|---" * (len(labels) + 1) + "|",
             _row("closest P (mm)", report["key_pose_position_errors_mm"]),
             _row("plate angle there (deg)", report["key_pose_angle_errors_deg"]),
             _row("BE length error (mm)", report["receiving_chain_errors_mm"]),
             _row("AF length error (mm)", report["carrier_chain_errors_mm"]), "",
             "Violations: " + ("; ".join(report["violations"]) or "none"), ""]
    return "\n".join(lines) + "\n"

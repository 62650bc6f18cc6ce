"""Five-bar reports as JSON (report.json) and Markdown (report.md): a designed mechanism
(``FiveBarResult``), a given design judged (``DesignEvaluation``), and the seedling support of either."""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from transplanter.cam.checks import Extreme
from transplanter.cam.timing import STAGES
from transplanter.fivebar.alternatives import RANKING_RULE
from transplanter.fivebar.key_pose_bands import QUANTITIES
from transplanter.fivebar.load_report import load_json, load_markdown
from transplanter.fivebar.nlp import BENDING_WEIGHT
from transplanter.fivebar.shaft_report import shafts_json, shafts_markdown
from transplanter.fivebar.solid_files import solids_note
from transplanter.solve.kkt_solver import kkt_factorisation
from transplanter.trains.planetary import printed_correction
from transplanter.trains.report import toothed_train_json, train_size_json, worst_mesh
from transplanter.trains.toothed_train import TrainSize

if TYPE_CHECKING:
    from transplanter.cam.table5 import Table5Evaluation
    from transplanter.fivebar.alternatives import ActiveBound, Alternative
    from transplanter.fivebar.evaluation import DesignEvaluation
    from transplanter.fivebar.linkage import FiveBar
    from transplanter.fivebar.relative_angle import RelativeAngle
    from transplanter.fivebar.result import FiveBarResult
    from transplanter.fivebar.support import SupportDesign


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


def relative_angle_json(relative: RelativeAngle, return_turns: np.ndarray) -> dict:
    """The motion rho(c): rho1, the spline's control values and the carrier turns at the return points (deg), as
    report.json and design.toml give it."""
    return {"rho1_deg": float(np.degrees(relative.rho1)),
            "control_values_deg": np.degrees(relative.coefficients).tolist(),
            "return_point_turns_deg": np.degrees(return_turns).tolist()}


def _stage_json(stage, name: str) -> dict:
    return {"pair": name, "center_distance": stage.center_distance, "closure_error_rad": stage.closure_error,
            "rolling_mismatch_mm": stage.rolling_mismatch_mm,
            "driver_radius_range": [float(stage.radius[0].min()), float(stage.radius[0].max())],
            "driven_radius_range": [float(stage.radius[1].min()), float(stage.radius[1].max())],
            "driver_convex": bool(np.all(stage.convexity[0] > 0)),
            "driven_convex": bool(np.all(stage.convexity[1] > 0)), "perimeters_mm": list(stage.perimeters)}


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
            "gears": (train_size_json(alternative.gears) if isinstance(alternative.gears, TrainSize)
                      else {"none": alternative.gears}),
            "nlp": {"status": design.status, "iterations": design.iterations, "objective": design.objective}}


def _cam_angles_deg(support: SupportDesign) -> dict[str, float]:
    """The cam's segments by stage name (deg of cam)."""
    return dict(zip(STAGES, (float(np.degrees(s.angle)) for s in support.cam.problem.segments), strict=True))


def _segments_source(support: SupportDesign) -> str:
    return ("typed (support.segments_deg)" if support.typed else
            "design stages: push pose 1 to the last key pose, receive to the first return point, return "
            "to the last return point, rest to the end of the turn")


def support_json(support: SupportDesign) -> dict:
    """The seedling support's part of report.json (mm, degrees); its cam as the cam report gives it."""
    spec, cam = support.spec, support.cam.to_json()
    return {
        "swing_deg": float(np.degrees(spec.swing)),
        "theta_cg_deg": {"low": float(np.degrees(spec.low_angle)), "high": float(np.degrees(spec.high_angle))},
        "bell_crank_kcg_deg": float(np.degrees(spec.bell_crank)),
        "clearance_to_receiving_plate_mm": support.clearance_mm,
        "clearance_least_at_carrier_turn_deg": float(np.degrees(support.clearance_turn)),
        "plate_x_mm": spec.linkage.plate_x, "heights_mm": list(spec.heights),
        "plate_height_range_mm": [float(np.nanmin(support.plate_height)), float(np.nanmax(support.plate_height))],
        "drive_ratio": spec.drive_ratio,
        "segments": {"cam_angles_deg": _cam_angles_deg(support), "source": _segments_source(support),
                     "carrier_stage_deg": dict(zip(STAGES, (float(v) for v in np.degrees(support.stages)),
                                                   strict=True))},
        "cam": {key: cam[key] for key in ("base_radius_mm", "direction", "follower", "laws", "max_pressure_angle_deg",
                                          "min_curvature_radius_mm", "undercut", "undercut_stretches",
                                          "roller_interference", "acceleration_jumps")},
        "cam_passed": support.cam.passed,
        "failures": support.failures,
        "table5": support.table5.to_json(),      # the published support, for comparison
    }


def fivebar_result_json(result: FiveBarResult) -> dict:
    """The report as plain JSON types (mm, degrees): the content of report.json."""
    problem, design, train, check = result.problem, result.design, result.train, result.verification
    toothed = toothed_train_json(result.toothed)
    relative = design.relative_angle
    k_printed, turn_printed = printed_correction(relative)
    region, chosen = result.region, result.chosen
    support = {"support": support_json(result.support)} if result.support else {}
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
        "picked": result.picked, "ranking_rule": RANKING_RULE,
        "alternatives": [alternative_json(a, k + 1, problem.poses[0]) for k, a in enumerate(result.alternatives)],
        "failed": [{"candidate": f.start + 1, "reason": f.reason} for f in result.failed],
        "design": design_json(design.mech, problem.poses[0]),
        "relative_angle": relative_angle_json(relative, design.stroke.carrier_turns),
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
                   "start_min_closure_margin": result.start.min_margin},
        "nlp": {"status": design.status, "iterations": design.iterations, "objective": design.objective,
                "bending_weight": BENDING_WEIGHT, "curvature_floor": design.curvature_floor,
                "convexity_note": design.convexity_note, "kkt_factorisation": kkt_factorisation()},
        "chosen_key_poses": chosen_key_poses_json(result),
        "key_pose_sets": [{"poses": pose_rows_json(trial.poses, trial.carrier_turns),
                           "feasible_five_bars": trial.feasible, "emptied_by": trial.binding or None}
                          for trial in result.band_trials],
        **result.pressure.to_json(),
        "load": load_json(result.loads),
        "shafts": shafts_json(result.shafts),
        "solids": solids_note(result),
        **support,
        **({"tolerance": result.tolerance.to_json()} if result.tolerance else {}),
        "timings_s": result.timings_s,
    }


def pose_rows_json(poses, turns) -> list[dict]:
    """Key poses (mm, rad) as the file gives them: x, y, angle_deg, carrier_turn_deg."""
    return [{"x": float(pose[0]), "y": float(pose[1]), "angle_deg": float(np.degrees(pose[2])),
             "carrier_turn_deg": float(np.degrees(turn))} for pose, turn in zip(poses, turns, strict=True)]


def chosen_key_poses_json(result: FiveBarResult) -> list[dict]:
    """Every key pose the design meets, with its label and, where the problem gave a band, which quantities it
    chose (``banded``)."""
    problem, bands = result.problem, result.pose_bands
    rows = pose_rows_json(problem.poses, problem.carrier_turns)
    return [{"label": label, **row,
             "banded": [] if bands is None else [QUANTITIES[q] for q in np.flatnonzero(bands.banded[k])]}
            for k, (label, row) in enumerate(zip(problem.labels, rows, strict=True))]


def _finite_or_none(value: float) -> float | None:
    """JSON has no NaN or infinity: a condition the evaluation did not reach is null."""
    return float(value) if np.isfinite(value) else None


def design_evaluation_json(evaluation: DesignEvaluation) -> dict:
    """The report as plain JSON types (mm, degrees; null where the whole-turn check was not reached): the
    content of report.json."""
    candidate = evaluation.candidate
    return {
        "source": evaluation.design.source,
        "key_pose_position_errors_mm": evaluation.position_errors_mm.tolist(),
        "key_pose_angle_errors_deg": evaluation.angle_errors_deg.tolist(),
        "receiving_chain_errors_mm": evaluation.chain_errors_mm[0].tolist(),
        "carrier_chain_errors_mm": evaluation.chain_errors_mm[1].tolist(),
        "violations": candidate.defects,
        "min_closure_margin": _finite_or_none(candidate.min_margin),
        "relative_angle_monotonic": evaluation.relative_angle_monotonic,
        "ratio_range": [_finite_or_none(v) for v in candidate.ratio_range],
        "assemblies_worst_position_error_mm": evaluation.alternatives,
        "design": design_json(evaluation.mech, evaluation.problem.poses[0]),
        **({"support": support_json(evaluation.support)} if evaluation.support else {}),
    }


def _row(label, values, digits=3):
    return f"| {label} | " + " | ".join(f"{v:.{digits}g}" if isinstance(v, float) else str(v) for v in values) + " |"


def to_markdown(result: FiveBarResult, files: Sequence[str] = ()) -> str:
    """report.md: key poses, the design, the whole turn, the gears, the alternatives, the region, the support,
    and the figures among ``files``."""
    problem, design, check, chosen, toothed = (result.problem, result.design, result.verification, result.chosen,
                                               result.toothed)
    labels = problem.labels
    lines = [f"# Five-bar seedling pushing mechanism: {problem.title or problem.source}", "",
             "## Key poses (forward simulation: gears rolling, then the linkage)", "",
             "| | " + " | ".join(labels) + " |", "|---" * (len(labels) + 1) + "|",
             _row("P position error (mm)", check.key_position_errors_mm.tolist()),
             _row("plate angle error (deg)", check.key_angle_errors_deg.tolist()), "",
             f"Return points reached within {max(check.return_point_errors_mm.tolist()):.3g} mm "
             f"(tolerance {problem.return_tolerance_mm:g} mm). "
             f"Gear trajectory against the designed one: {check.roundtrip_max_error_mm:.3g} mm at most; "
             f"pitch-curve contact gap {check.contact_gap_mm:.3g} mm.", "",
             "## Design (pose 1)", "", "| quantity | value |", "|---|---|"]
    lines += [f"| {name} | {value if isinstance(value, (str, list)) else round(value, 4)} |"
              for name, value in design_json(design.mech, problem.poses[0]).items()]
    low, high = check.ratio_range
    lines += ["", "## Whole turn", "",
              f"- smallest transmission angle at E (between EF and BE): {np.degrees(chosen.transmission_angle):.2f} "
              f"deg at carrier turn {np.degrees(chosen.transmission_turn):.1f} deg; smallest closure angle EBF: "
              f"{np.degrees(chosen.closure_angle):.2f} deg",
              f"- smallest closure margin sin²(EBF): {check.min_closure_margin:.5f} "
              f"(required {problem.min_closure_margin}); eq (10) discriminant ≥ {check.min_discriminant:.4g} mm⁴",
              "- active bounds: " + (", ".join(_bound(b) for b in chosen.active_bounds) or "none"),
              f"- relative angle strictly increasing: {check.relative_angle_monotonic}; total ratio i0 in "
              f"[{low:.4f}, {high:.4f}]", ""]
    k_printed, turn_printed = printed_correction(design.relative_angle)
    a1, a2 = toothed.train.center_distances
    mesh = worst_mesh(toothed)
    lines += ["## Gears (eq 11-13)", "",
              f"Correction factor k = {result.train.correction:.6f}. Eq (12) as printed (integrating over the relative "
              f"angle) gives k = {k_printed:.6f}, with which the first intermediate gear turns "
              f"{np.degrees(turn_printed):.3f} deg per sun turn instead of 360.", "",
              f"Module {toothed.module:g} mm, pressure angle {np.degrees(toothed.pressure_angle):g} deg, "
              f"{toothed.layout} carrier: a1 = {a1:.4f} mm, a2 = {a2:.4f} mm, the intermediate shaft at "
              f"({toothed.shaft[0]:.3f}, {toothed.shaft[1]:.3f}) mm, bent {np.degrees(toothed.bend_angle):.2f} deg "
              "from O-A.", "",
              *([f"Pitch curves in the design NLP: {design.convexity_note}.", ""] if design.convexity_note else []),
              "| gear | role | teeth | convex | smallest convex curvature radius (mm) | cutter | why |",
              "|---|---|---|---|---|---|---|"]
    lines += [f"| {g.name} | {g.role} | {g.teeth} | {g.convex} | {g.min_curvature_radius:.3f} | {g.cutter} | "
              f"{g.reason} |" for g in toothed.gears]
    lines += ["", f"Tooth mesh over a turn (teeth turned by the designed motion): largest overlap "
              f"{mesh.max_overlap_mm:.4f} mm, smallest clearance {mesh.min_clearance_mm:.4f} mm, transmission "
              f"error {mesh.transmission_error_deg:.4f} deg: {'FAILED' if toothed.mesh_failures else 'passed'}.", ""]
    lines += _alternatives(result)
    region = result.region
    lines += ["", "## Solution region", "",
              f"{int(region.receiving.kept.sum())} of {len(region.receiving.fixed)} B-E dyads and "
              f"{int(region.carrier.kept.sum())} of {len(region.carrier.fixed)} A-F dyads within ranges; "
              f"{len(region.feasible)} of {len(region.candidates)} five-bars feasible (removed by: "
              f"{region.pair_defects}).", "",
              f"NLP: {design.status} in {design.iterations} iterations; KKT systems factored by "
              f"{kkt_factorisation()}.", ""]
    lines += _chosen_poses_markdown(result)
    lines += ["## Loads (quasi-static, frictionless hinges, a lossless train)", "", *load_markdown(result.loads), "",
              result.pressure.summary(), ""]
    lines += support_markdown(result.support)
    lines += result.tolerance.to_markdown() if result.tolerance else []
    lines += ["## Shafts and bores", "", *shafts_markdown(result.shafts), f"- {solids_note(result)}", ""]
    lines += [f"![{name}]({name})" for name in files if name.endswith(".png")]
    return "\n".join(lines) + "\n"


def _chosen_poses_markdown(result: FiveBarResult) -> list[str]:
    """The key poses the design chose inside their bands, and the pose sets the region was built for."""
    bands = result.pose_bands
    if bands is None:
        return []
    problem = result.problem
    lines = ["## Key poses chosen inside their bands", "",
             "| pose | x (mm) | y (mm) | angle (deg) | carrier turn (deg) | banded |", "|---|---|---|---|---|---|"]
    for k, row in enumerate(pose_rows_json(problem.poses, problem.carrier_turns)):
        banded = ", ".join(QUANTITIES[q] for q in np.flatnonzero(bands.banded[k])) or "none"
        lines.append(f"| {problem.labels[k]} | {row['x']:.3f} | {row['y']:.3f} | {row['angle_deg']:.3f} | "
                     f"{row['carrier_turn_deg']:.3f} | {banded} |")
    trials = result.band_trials
    lines += ["", f"The region was built for {len(trials)} pose set{'s' * (len(trials) > 1)} (the bands' centres "
              "first): " + "; ".join(f"{k + 1}: {trial.feasible} feasible five-bars" if trial.feasible else
                                     f"{k + 1}: none ({trial.binding})" for k, trial in enumerate(trials)) + ".", ""]
    return lines


def _bound(bound: ActiveBound) -> str:
    return f"{bound.name} {'>=' if bound.side == 'lower' else '<='} {bound.limit:g}"


def _gear_sizes(gears: TrainSize | str | None) -> str:
    if not isinstance(gears, TrainSize):
        return f"none: {gears}"
    (a1, a2), radii = gears.center_distances, gears.largest_pitch_radius
    return (f"{gears.counts[0]} / {gears.counts[1]} at m {gears.module:g} ({'/'.join(gears.cutters)}), "
            f"{a1:.1f} / {a2:.1f}, {max(radii):.1f}")


def _alternative_row(alternative: Alternative, rank: int, picked: int) -> str:
    mech = alternative.design.mech
    mark = " (built)" if rank == picked else ""
    low, high = alternative.ratio_range
    return (f"| {rank}{mark} | {mech.carrier_length:.2f} | {mech.rod_length:.2f} | {mech.link_length:.2f} | "
            f"{mech.receiving_length:.2f} | {mech.ep:.2f} | {mech.fp:.2f} | "
            f"({mech.hinge_b[0]:.1f}, {mech.hinge_b[1]:.1f}) | "
            f"{np.degrees(alternative.transmission_angle):.2f} at {np.degrees(alternative.transmission_turn):.1f} | "
            f"{np.degrees(alternative.closure_angle):.2f} | {low:.3f}-{high:.3f} | "
            f"{max(alternative.return_misses_mm.tolist()):.3g} | {_gear_sizes(alternative.gears)} | "
            f"{', '.join(_bound(b) for b in alternative.active_bounds) or 'none'} | "
            f"{', '.join(str(k + 1) for k in alternative.starts)}"
            + (f"; then {alternative.restroke}" if alternative.restroke else "") + " |")


def _alternatives(result: FiveBarResult) -> list[str]:
    """The table of the ranked alternatives and the list of the candidates that failed."""
    lines = ["", "## Alternatives", "",
             f"{RANKING_RULE} Alternative {result.picked} is built (`--pick N` builds another).", "",
             "| # | OA | AF | EF | BE | EP | FP | B (mm) | min at E (deg) at turn | min EBF (deg) | i0 range | "
             "largest return miss (mm) | gears: teeth, a1 / a2, largest pitch radius (mm) | active bounds | "
             "from candidates |", "|---" * 15 + "|"]
    lines += [_alternative_row(alternative, k + 1, result.picked) for k, alternative in enumerate(result.alternatives)]
    lines += ["", "Lengths in mm; turns are the carrier's, clockwise from pose 1 (deg)."]
    if result.failed:
        lines += ["", "Candidates whose refinement failed:", ""]
        lines += [f"- candidate {failure.start + 1}: {failure.reason}" for failure in result.failed]
    return lines


def evaluation_markdown(evaluation: DesignEvaluation) -> str:
    """report.md of a given design: the key poses, the chains, the violations and the support."""
    labels = evaluation.problem.labels
    receiving, carrier = evaluation.chain_errors_mm
    lines = [f"# Given design {evaluation.design.source}", "", "| | " + " | ".join(labels) + " |",
             "|---" * (len(labels) + 1) + "|",
             _row("closest P (mm)", evaluation.position_errors_mm.tolist()),
             _row("plate angle there (deg)", evaluation.angle_errors_deg.tolist()),
             _row("BE length error (mm)", receiving.tolist()),
             _row("AF length error (mm)", carrier.tolist()), "",
             "Violations: " + ("; ".join(evaluation.candidate.defects) or "none"), ""]
    lines += support_markdown(evaluation.support)
    return "\n".join(lines) + "\n"


def support_markdown(support: SupportDesign | None) -> list[str]:
    """The "Seedling support" section (none without ``[support]``)."""
    if support is None:
        return []
    spec, cam = support.spec, support.cam
    checks = cam.checks
    angles = ", ".join(f"{name} {value:.2f}" for name, value in _cam_angles_deg(support).items())
    laws = sorted({s.law for s in cam.problem.segments if s.law})
    return ["## Seedling support (cam and rocker-slider, eq 14-15)", "",
            f"- plate line x_Z = {spec.linkage.plate_x:g} mm, heights {spec.heights[0]:g} to {spec.heights[1]:g} mm; "
            f"rocker theta_CG {np.degrees(spec.low_angle):.3f} to {np.degrees(spec.high_angle):.3f} deg, swing psi = "
            f"{np.degrees(spec.swing):.3f} deg; bell crank KCG {np.degrees(spec.bell_crank):.3f} deg",
            f"- clearance to the receiving plate (min x_E - x_Z): {support.clearance_mm:.3f} mm at "
            f"carrier turn {np.degrees(support.clearance_turn):.1f} deg",
            f"- cam segments (deg of cam; drive ratio {spec.drive_ratio:g}, cam turning with the carrier): {angles}; "
            f"from {_segments_source(support)}",
            f"- cam: base radius {cam.base_radius:g} mm; largest pressure angle rise "
            f"{np.degrees(checks.pressure['rise'].value):.3f} deg, return "
            f"{np.degrees(checks.pressure['return'].value):.3f} deg (limit "
            f"{round(float(np.degrees(cam.problem.pressure_limit)), 9):g}); smallest convex pitch radius "
            f"{_pitch_radius_text(checks.min_pitch_radius)}; undercut: {'yes' if checks.undercut else 'no'}; "
            f"{len(checks.acceleration_jumps)} acceleration jumps ({', '.join(laws)})",
            "- " + ("; ".join(support.failures) if support.failures else "passes its checks"),
            f"- {table5_line(support.table5)}", ""]


def _pitch_radius_text(smallest: Extreme | None) -> str:
    """The cam's smallest convex pitch radius, or that it has none (a flat-faced follower's cam)."""
    return "no pitch curve" if smallest is None else f"{smallest.value:.3f} mm"


def table5_line(table5: Table5Evaluation) -> str:
    """One sentence on the published support (Wang et al. 2025 Table 5) as ``cam.table5`` evaluates it."""
    report = table5.report
    printed, datum = report["printed"], report["heights_from_datum"][0]
    lifting = next(c for c in report["perpendicular_layout"]["cams"] if c["lifts_plate"])
    worst = max(lifting["max_pressure_angle_deg"][k] for k in ("rise", "return"))
    return (f"Table 5 as printed {'assembles' if printed['assembles'] else 'does not assemble'} "
            f"(|CH| {printed['distance_c_to_h_mm'][0]:.2f} / {printed['distance_c_to_h_mm'][1]:.2f} mm against a "
            f"reach of {printed['reach_mm'][0]:g}-{printed['reach_mm'][1]:g} mm); heights from a datum "
            f"y0 = {datum['datum_y0_mm']:.2f} mm give psi = {datum['swing_deg']:.2f} deg; on the square cam layout the "
            f"roller side that lifts the plate ({lifting['roller_side']}) reaches a pressure angle of {worst:.2f} deg "
            f"(docs/cam.md)")

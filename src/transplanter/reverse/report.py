"""A reverse design as JSON (report.json) and Markdown (report.md): the path, the arm's motion, the
monotonicity verdict with the changes that would pass, and the gear train with its round trip."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from transplanter.gears.mesh_check import OVERLAP_MODULES
from transplanter.geometry.closed_trajectory import TWO_PI
from transplanter.reverse.arm_inverse import BRANCH_NAMES, DIRECTION_NAMES
from transplanter.reverse.idler_train import IdlerTrain
from transplanter.reverse.pitch_corners import pitch_corners
from transplanter.reverse.ratio_extremes import ratio_range
from transplanter.reverse.solid_files import solids_note
from transplanter.reverse.tolerance_model import path_accuracy_mm
from transplanter.trains.planetary import printed_peak_to_valley_turn
from transplanter.trains.report import toothed_train_json, worst_mesh

if TYPE_CHECKING:
    from transplanter.reverse.arm_inverse import ArmMotion
    from transplanter.reverse.monotonicity import Violation
    from transplanter.reverse.result import ReverseResult
    from transplanter.trains.planetary import PlanetaryTrain
    from transplanter.trains.toothed_train import ToothedTrain


@dataclass(frozen=True)
class GearRow:
    """One gear of the train: radius range (mm), convex all round, pitch perimeter (mm), teeth at the module."""

    name: str
    radius_range: tuple[float, float]
    convex: bool
    perimeter: float
    teeth_at_module: float


def _gear(name: str, radius: np.ndarray, convexity: np.ndarray, perimeter: float, module: float) -> GearRow:
    return GearRow(name, (float(radius.min()), float(radius.max())), bool(np.all(convexity > 0)), perimeter,
                   perimeter / (np.pi * module))


def gear_rows(train: PlanetaryTrain | IdlerTrain, module: float) -> list[GearRow]:
    """Sun to planet: a sun-idler-planet train has three gears, a planetary train four."""
    one, two = train.stage_one, train.stage_two
    rows = [_gear("sun", one.radius[0], one.convexity[0], one.perimeters[0], module)]
    if isinstance(train, IdlerTrain):
        return rows + [_gear("idler", one.radius[1], one.convexity[1], one.perimeters[1], module),
                       _gear("planet", two.radius[1], two.convexity[1], two.perimeters[1], module)]
    return rows + [_gear("first intermediate", one.radius[1], one.convexity[1], one.perimeters[1], module),
                   _gear("second intermediate", two.radius[0], two.convexity[0], two.perimeters[0], module),
                   _gear("planet", two.radius[1], two.convexity[1], two.perimeters[1], module)]


def branch_stretches(result: ReverseResult) -> list[tuple[float, float, str]]:
    """Stretches of the path parameter u (in turns, from, to) and the arm branch on each."""
    motion = result.motion
    cuts = [0.0] + [t.parameter for t in motion.touches] + [TWO_PI]
    return [(a / TWO_PI, b / TWO_PI, BRANCH_NAMES[int(motion.branch(np.array((a + b) / 2)))])
            for a, b in zip(cuts[:-1], cuts[1:], strict=True) if b > a]


def _fit_residual(result: ReverseResult) -> float | None:
    """How far the curve fitted to sampled points misses them (mm); None for a path given as a curve."""
    problem = result.problem
    return float(result.trajectory.sample_misses(problem.points).max()) if problem.kind == "samples" else None


def _lengths_from(result: ReverseResult) -> str:
    return "path extremes (the rice-transplanter paper eq 1-2)" if result.lengths_derived else "problem file"


def _closure_errors(train: PlanetaryTrain | IdlerTrain) -> list[float]:
    return [train.stage_one.closure_error, train.stage_two.closure_error]


def _printed_turn_deg(result: ReverseResult) -> float | None:
    """The intermediate gear's turn per cycle with the reverse-gear-design paper's split as printed (deg); None
    unless a planetary train splits the ratio peak to valley."""
    if result.problem.split != "peak_to_valley" or result.relative is None or isinstance(result.train, IdlerTrain):
        return None
    return float(np.degrees(printed_peak_to_valley_turn(result.relative, result.problem.peak_to_valley)))


def toothed_train_markdown(toothed: ToothedTrain) -> list[str]:
    """The whole-tooth train: layout, counts, how each gear is cut and why, the mesh check over a turn."""
    a1, a2 = toothed.train.center_distances
    worst = worst_mesh(toothed)
    limit = OVERLAP_MODULES * toothed.module
    lines = [f"## Toothed train ({toothed.layout} carrier)", "",
             f"- Module {toothed.module:g} mm, pressure angle {np.degrees(toothed.pressure_angle):g} deg; teeth "
             f"Z1 = {toothed.counts[0]} (sun, first intermediate), Z2 = {toothed.counts[1]} (second intermediate, "
             f"planet); centre distances a1 = {a1:.6f} mm, a2 = {a2:.6f} mm; the intermediate shaft "
             f"{np.degrees(toothed.bend_angle):.4f} deg off the line pivot-planet at O, at ({toothed.shaft[0]:.4f}, "
             f"{toothed.shaft[1]:.4f}) mm in the carrier frame",
             f"- Mesh check over a turn ({'FAILED' if toothed.mesh_failures else 'passed'}): largest overlap "
             f"{worst.max_overlap_mm:.5f} mm ({worst.max_overlap_mm / toothed.module:.5f} module; allowed {limit:.4f} "
             f"mm), smallest clearance {worst.min_clearance_mm:.5f} mm, transmission error "
             f"{worst.transmission_error_deg:.4f} deg", "",
             "| gear | teeth | cutter | why |", "| --- | --- | --- | --- |"]
    lines += [f"| {g.name} | {g.teeth} | {g.cutter} | {g.reason} |" for g in toothed.gears]
    lines += [f"- {text}" for text in toothed.failures]
    return lines + [""]


def corner_lines(motion: ArmMotion, train: PlanetaryTrain) -> list[str]:
    """The pitch curves' corners (``pitch_corners``), one line each, under a heading line; none: []."""
    corners = [c for c in pitch_corners(motion, train) if c.corner]
    if not corners:
        return []
    return ["", "Pitch-curve corners where the path touches a reach circle on a knot of its spline (the tangent's "
            "turn; a hollow is one no rack cuts):"] + [
        f"- {c.gear}: {np.degrees(c.tangent_turn):+.4f} deg at carrier turn {np.degrees(c.carrier_turn):.2f} deg"
        f" ({'hollow' if c.hollow else 'convex'})" for c in corners]


def violation_json(violation: Violation) -> dict:
    return {"condition": violation.condition, "u": [violation.u_start, violation.u_end], "worst": violation.worst,
            "message": violation.message}


def reverse_result_json(result: ReverseResult) -> dict:
    """The report as plain JSON types (mm, degrees; u in turns): the content of report.json."""
    problem, motion = result.problem, result.motion
    report = {
        "title": problem.title, "source": problem.source,
        "trajectory": {"kind": problem.kind, "points": len(problem.points), "pivot": problem.pivot.tolist(),
                       "farthest_mm": result.extremes[0], "nearest_mm": result.extremes[1],
                       "fit_residual_mm": _fit_residual(result)},
        "carrier_length": motion.carrier_length, "arm_length": motion.arm_length,
        "lengths_from": _lengths_from(result),
        "direction": DIRECTION_NAMES[motion.direction],
        "touches": [{"u": t.parameter / TWO_PI, "circle": t.circle, "gap_mm": t.gap_mm} for t in motion.touches],
        "branch_segments": [{"u": [start, end], "branch": branch} for start, end, branch in branch_stretches(result)],
        "branch_switches_u": [t.parameter / TWO_PI for t in motion.touches],
        "monotonic": result.monotonic,
        "violations": [violation_json(v) for v in result.violations],
        "fix_hints": result.hints,
        "topology": problem.topology, "split": problem.split,
    }
    train, verification = result.train, result.verification
    if train is None or verification is None:          # no train: the path fails the monotonicity criterion
        return report
    report.update({
        "ratio_range": list(ratio_range(result.motion)),
        "gears": [{"gear": g.name, "radius_range_mm": list(g.radius_range), "convex": g.convex,
                   "perimeter_mm": g.perimeter, "teeth_at_module": g.teeth_at_module}
                  for g in gear_rows(train, problem.module)],
        "gear_closure_errors": _closure_errors(train),
        "roundtrip_max_error_mm": verification.max_error_mm,
        "contact_gap_max_mm": max(float(np.abs(g).max()) for g in verification.contact_gaps_mm),
    })
    if not isinstance(train, IdlerTrain):
        report["pitch_curve_corners"] = [
            {"gear": c.gear, "carrier_turn_deg": float(np.degrees(c.carrier_turn)),
             "tangent_turn_deg": float(np.degrees(c.tangent_turn)), "hollow": c.hollow}
            for c in pitch_corners(result.motion, train)]
    if result.toothed is not None:
        report["toothed_train"] = toothed_train_json(result.toothed)
        report["solids"] = solids_note(result.toothed, problem)
    if result.teeth_note:
        report["teeth_note"] = result.teeth_note
    if result.tolerance is not None:
        report["tolerance"] = {**result.tolerance.to_json(), "path_accuracy_mm": path_accuracy_mm(result)}
    if result.tolerance_note:
        report["tolerance_note"] = result.tolerance_note
    if isinstance(train, IdlerTrain):
        report["idler_iteration"] = {"iterations": train.iterations, "settled": bool(train.converged),
                                     "eq5_model_residual": train.model_residual, "correction_x": train.correction,
                                     "center_distance_mm": train.center_distance}
    else:
        report.update({"center_distances": list(train.center_distances), "correction_factor_k": train.correction,
                       "stage_one_exponent": train.exponent})
        if result.geometry is not None:
            report["carrier_bend_deg"] = float(np.degrees(result.geometry.bend))
        if problem.split == "peak_to_valley":
            report["printed_peak_to_valley_intermediate_turn_deg"] = _printed_turn_deg(result)
    return report


def to_markdown(result: ReverseResult, files: Sequence[str] = ()) -> str:
    """report.md: the path, the arm, the criterion (with the changes that would pass), the train, the figures."""
    problem, motion = result.problem, result.motion
    fit = _fit_residual(result)
    switches = [t.parameter / TWO_PI for t in motion.touches]
    lines = [f"# Reverse design: {problem.title or problem.source}", "",
             f"- Path: {len(problem.points)} {problem.kind.replace('_', ' ')}, farthest {result.extremes[0]:.4f} mm "
             f"and nearest {result.extremes[1]:.4f} mm from the pivot {problem.pivot.tolist()}"
             + (f"; the curve fitted to the samples misses them by up to {fit:.3g} mm" if fit is not None else ""),
             f"- Carrier s = {motion.carrier_length:.4f} mm, arm l = {motion.arm_length:.4f} mm "
             f"({_lengths_from(result)}), carrier turning {DIRECTION_NAMES[motion.direction]}",
             "- Branches: " + ", ".join(f"{branch} on u {start:.4f}-{end:.4f}"
                                        for start, end, branch in branch_stretches(result))
             + (f"; switches at u = {', '.join(f'{u:.4f}' for u in switches)} (the path touches "
                "the reach circles there)" if switches else ""),
             f"- Monotonicity criterion (the reverse-gear-design paper): {'met' if result.monotonic else 'NOT met'}"]
    lines += [f"  - {violation.condition}: {violation.message}" for violation in result.violations]
    lines += [f"  - would pass with: {hint}" for hint in result.hints]
    train, verification = result.train, result.verification
    if train is not None and verification is not None:         # a train: the path meets the criterion
        low, high = ratio_range(result.motion)
        miss = verification.max_error_mm
        lines += [f"- Train: {problem.topology}, split {problem.split}; total ratio i0 from {low:.4f} to {high:.4f}",
                  f"- Gear closure errors (rad): {', '.join(f'{e:.2e}' for e in _closure_errors(train))}",
                  f"- Round trip (gears rolled from their pitch curves, tip rebuilt): largest miss {miss:.3e} mm", "",
                  "| gear | radius min (mm) | radius max (mm) | convex | perimeter (mm) | teeth at the module |",
                  "| --- | --- | --- | --- | --- | --- |"]
        lines += [f"| {g.name} | {g.radius_range[0]:.3f} | {g.radius_range[1]:.3f} | {g.convex} | "
                  f"{g.perimeter:.3f} | {g.teeth_at_module:.2f} |" for g in gear_rows(train, problem.module)]
        printed = _printed_turn_deg(result)
        if isinstance(train, IdlerTrain):
            lines += ["", f"The rice-transplanter paper's iteration: {train.iterations} iterations, "
                      f"settled: {bool(train.converged)}, eq (5) model residual {train.model_residual:.3e}; the train "
                      f"as built misses the path by {miss:.3f} mm (see docs/reverse.md, 'Published findings')."]
        else:
            lines += corner_lines(result.motion, train)
        if printed is not None:
            lines += ["", "The reverse-gear-design paper's split as printed (i1 = i25 bs) would turn the intermediate "
                      f"gear {printed:.3f} deg per cycle (360 closes)."]
    lines += [""] + (toothed_train_markdown(result.toothed) if result.toothed else [])
    lines += [f"- {solids_note(result.toothed, problem)}", ""] if result.toothed else []
    lines += [f"- Teeth: {result.teeth_note}", ""] if result.teeth_note else []
    lines += (result.tolerance.to_markdown() + [_path_accuracy_line(result), ""] if result.tolerance else [])
    lines += [f"- Tolerances: {result.tolerance_note}", ""] if result.tolerance_note else []
    lines += [f"![{name}]({name})" for name in files if name.endswith(".png")]
    return "\n".join(lines) + "\n"


def _path_accuracy_line(result: ReverseResult) -> str:
    """What the tolerance analysis's path accuracy asks of a built train."""
    reach = result.motion.carrier_length + result.motion.arm_length
    accuracy = path_accuracy_mm(result)
    return (f"Path accuracy: a built tip within {accuracy:.4g} mm ({100 * accuracy / reach:.3g} % of the reach "
            "s + l) of the designed tip at every carrier turn (`[tolerances]` path_accuracy_mm).")

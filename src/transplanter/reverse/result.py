"""A reverse design (arm motion, monotonicity verdict, gear train, round trip), and its JSON
(the content of report.json)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.closed_trajectory import ClosedTrajectory
from transplanter.geometry.planar import TWO_PI
from transplanter.reverse.arm_inverse import BRANCH_NAMES, DIRECTION_NAMES, ArmMotion
from transplanter.reverse.carrier_frame_motion import CarrierFrameMotion
from transplanter.reverse.idler_train import IdlerTrain
from transplanter.reverse.monotonicity import Violation
from transplanter.reverse.problem import ReverseProblem
from transplanter.reverse.verification import CarrierGeometry, ReverseVerification
from transplanter.trains.planetary import PlanetaryTrain, printed_peak_to_valley_turn

#: A train whose rolled tip strays further than this fraction of the reach s + l from the path fails the result
#: (2.5e-6 mm on the rice path; the misses measured are 1e-11 to 1e-10 of it at scales 1e-3 to 1e6).
ROUNDTRIP_TOLERANCE = 1e-8


def _gear(name: str, radius: np.ndarray, convexity: np.ndarray, perimeter: float, module: float) -> dict:
    return {"gear": name, "radius_range_mm": [float(radius.min()), float(radius.max())],
            "convex": bool(np.all(convexity > 0)), "perimeter_mm": perimeter,
            "teeth_at_module": perimeter / (np.pi * module)}


@dataclass(frozen=True)
class ReverseResult:
    """A reverse design for a ``ReverseProblem``.

    Attributes
    ----------
    problem : ReverseProblem
        The problem solved (mm).
    trajectory : ClosedTrajectory
        The closed path of the arm tip about the pivot (mm), over the parameter u in [0, 2 pi).
    extremes : (float, float)
        Farthest and nearest |P| from the pivot (mm).
    lengths_derived : bool
        Whether the carrier and arm lengths came from the path's extremes (the rice-transplanter paper eq 1-2).
    motion : ArmMotion
        Carrier and arm angles along the path (rad), lengths (mm), branch switches.
    violations : list of Violation
        Where the monotonicity criterion (the reverse-gear-design paper) fails; empty when it passes.
    hints : list of str
        Changes that would pass, when it fails.
    relative : CarrierFrameMotion or None
        The arm's angle relative to the carrier as a function of the carrier turn (rad).
    geometry : CarrierGeometry or None
        Bent carrier of the pick-up topology (mm, rad); None for a straight one.
    train : PlanetaryTrain or IdlerTrain or None
        The gear train (pitch curves in mm); None when the criterion fails.
    verification : ReverseVerification or None
        The tip rebuilt from the rolled gears against the path (mm).
    """

    problem: ReverseProblem
    trajectory: ClosedTrajectory
    extremes: tuple[float, float]
    lengths_derived: bool
    motion: ArmMotion
    violations: list[Violation]
    hints: list[str]
    relative: CarrierFrameMotion | None = None
    geometry: CarrierGeometry | None = None
    train: PlanetaryTrain | IdlerTrain | None = None
    verification: ReverseVerification | None = None

    @property
    def monotonic(self) -> bool:
        """Whether the path meets the monotonicity criterion (then it has a train)."""
        return not self.violations

    @property
    def failures(self) -> list[str]:
        """Why there is no train (where the path fails the monotonicity criterion), or why the train fails (rolled
        from its pitch curves, it misses the path by more than ROUNDTRIP_TOLERANCE of the reach); empty when both
        pass."""
        if not self.monotonic:
            return ["the path fails the monotonicity criterion: " + "; ".join(v.message for v in self.violations)]
        miss, reach = self.verification.max_error_mm, self.motion.carrier_length + self.motion.arm_length
        if miss <= ROUNDTRIP_TOLERANCE * reach:
            return []
        return [f"the {self.problem.topology} train, rolled from its pitch curves, misses the path by up to "
                f"{miss:.4g} mm (more than {ROUNDTRIP_TOLERANCE:g} of the reach s + l = {reach:.6g} mm)"]

    @property
    def passed(self) -> bool:
        return not self.failures

    def branch_segments(self) -> list[dict]:
        """Stretches of the path parameter u (in turns) and the arm branch on each."""
        motion = self.motion
        cuts = [0.0] + [t.parameter for t in motion.touches] + [TWO_PI]
        return [{"u": [a / TWO_PI, b / TWO_PI], "branch": BRANCH_NAMES[int(motion.branch(np.array((a + b) / 2)))]}
                for a, b in zip(cuts[:-1], cuts[1:]) if b > a]

    def _gears_json(self) -> tuple[list[dict], list[float]]:
        train, module = self.train, self.problem.module
        one, two = train.stage_one, train.stage_two
        gears = [_gear("sun", one.radius[0], one.convexity[0], one.perimeters[0], module)]
        if isinstance(train, IdlerTrain):
            gears += [_gear("idler", one.radius[1], one.convexity[1], one.perimeters[1], module),
                      _gear("planet", two.radius[1], two.convexity[1], two.perimeters[1], module)]
            return gears, [one.closure_error, two.closure_error]
        gears += [_gear("first intermediate", one.radius[1], one.convexity[1], one.perimeters[1], module),
                  _gear("second intermediate", two.radius[0], two.convexity[0], two.perimeters[0], module),
                  _gear("planet", two.radius[1], two.convexity[1], two.perimeters[1], module)]
        return gears, [one.closure_error, two.closure_error]

    def to_json(self) -> dict:
        """The report as plain JSON types (mm, degrees; u in turns): the content of report.json."""
        problem, motion = self.problem, self.motion
        report = {
            "title": problem.title, "source": problem.source,
            "trajectory": {"kind": problem.kind, "points": len(problem.points), "pivot": problem.pivot.tolist(),
                           "farthest_mm": self.extremes[0], "nearest_mm": self.extremes[1],
                           "fit_residual_mm": (float(self.trajectory.sample_misses(problem.points).max())
                                               if problem.kind == "samples" else None)},
            "carrier_length": motion.carrier_length, "arm_length": motion.arm_length,
            "lengths_from": "path extremes (the rice-transplanter paper eq 1-2)" if self.lengths_derived else "problem file",
            "direction": DIRECTION_NAMES[motion.direction],
            "touches": [{"u": t.parameter / TWO_PI, "circle": t.circle, "gap_mm": t.gap_mm} for t in motion.touches],
            "branch_segments": self.branch_segments(),
            "branch_switches_u": [t.parameter / TWO_PI for t in motion.touches],
            "monotonic": self.monotonic,
            "violations": [v.to_json() for v in self.violations],
            "fix_hints": self.hints,
            "topology": problem.topology, "split": problem.split,
        }
        if not self.monotonic:
            return report
        ratio = motion.total_ratio()
        gears, closure = self._gears_json()
        report.update({
            "ratio_range": [float(ratio.min()), float(ratio.max())],
            "gears": gears, "gear_closure_errors": closure,
            "roundtrip_max_error_mm": self.verification.max_error_mm,
            "contact_gap_max_mm": max(float(np.abs(g).max()) for g in self.verification.contact_gaps_mm),
        })
        train = self.train
        if isinstance(train, IdlerTrain):
            report["idler_iteration"] = {"iterations": train.iterations, "settled": bool(train.converged),
                                         "eq5_model_residual": train.model_residual, "correction_x": train.correction,
                                         "center_distance_mm": train.center_distance}
        else:
            report.update({"center_distances": list(train.center_distances), "correction_factor_k": train.correction,
                           "stage_one_exponent": train.exponent})
            if self.geometry is not None:
                report["carrier_bend_deg"] = float(np.degrees(self.geometry.bend))
            if problem.split == "peak_to_valley":
                report["printed_peak_to_valley_intermediate_turn_deg"] = float(
                    np.degrees(printed_peak_to_valley_turn(self.relative, problem.peak_to_valley)))
        return report

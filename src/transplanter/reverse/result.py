"""A reverse design (arm motion, monotonicity verdict, gear train, round trip), and the checks it passes."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

from transplanter import progress
from transplanter.command_result import CommandResult
from transplanter.geometry.closed_trajectory import ClosedTrajectory
from transplanter.reverse.arm_inverse import ArmMotion
from transplanter.reverse.carrier_frame_motion import CarrierFrameMotion
from transplanter.reverse.idler_train import IdlerTrain
from transplanter.reverse.monotonicity import Violation
from transplanter.reverse.problem import ReverseProblem
from transplanter.reverse.verification import CarrierGeometry, ReverseVerification
from transplanter.tolerance import ToleranceAnalysis, ToleranceModel
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.trains.toothed_train import ToothedTrain

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer

#: A train whose rolled tip strays further than this fraction of the reach s + l from the path fails the result
#: (2.5e-6 mm on the rice path; the misses measured are 1e-11 to 1e-10 of it at scales 1e-3 to 1e6).
ROUNDTRIP_TOLERANCE = 1e-8


@dataclass(frozen=True)
class ReverseResult(CommandResult):
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
    tolerance : ToleranceAnalysis or None
        How precise the built train and arm will be (``tolerance.analyse``), else None (``tolerance=False``, or a
        path without a train).
    tolerance_note : str
        Why a train has no tolerance analysis (a dimension without a default tolerance), else "".
    toothed : ToothedTrain or None
        The four-gear train with whole teeth, cut and mesh-checked (``reverse.whole_teeth``); ``train`` is then its
        pitch-curve train. None for sun-idler-planet, or when no whole counts fit (``teeth_note`` says why).
    teeth_note : str
        Why a four-gear train has no teeth, else "".
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
    tolerance: ToleranceAnalysis | None = None
    tolerance_note: str = ""
    toothed: ToothedTrain | None = None
    teeth_note: str = ""

    @property
    def source(self) -> str:
        return self.problem.source

    @property
    def monotonic(self) -> bool:
        """Whether the path meets the monotonicity criterion (then it has a train)."""
        return not self.violations

    @property
    def produced(self) -> bool:
        """A train is made only for a path that meets the monotonicity criterion."""
        return self.monotonic

    @property
    def failures(self) -> list[str]:
        """Why there is no train (where the path fails the monotonicity criterion), or why the train fails (rolled
        from its pitch curves, it misses the path by more than ROUNDTRIP_TOLERANCE of the reach); empty when both
        pass."""
        if not self.monotonic or self.verification is None:      # a train, and its verification, need the former
            return ["the path fails the monotonicity criterion: " + "; ".join(v.message for v in self.violations)]
        miss, reach = self.verification.max_error_mm, self.motion.carrier_length + self.motion.arm_length
        found = [] if miss <= ROUNDTRIP_TOLERANCE * reach else [
            f"the {self.problem.topology} train, rolled from its pitch curves, misses the path by up to "
            f"{miss:.4g} mm (more than {ROUNDTRIP_TOLERANCE:g} of the reach s + l = {reach:.6g} mm)"]
        if self.toothed is None:
            return found
        from transplanter.reverse.gear_files import bore_failures

        return (found + [f"mesh check: {text}" for text in self.toothed.mesh_failures] + self.toothed.crossing_failures
                + bore_failures(self.toothed))

    def tolerance_model(self) -> ToleranceModel:
        """The built train and arm as a function of their manufactured dimensions (``reverse.tolerance_model``)."""
        from transplanter.reverse.tolerance_model import tolerance_model

        return tolerance_model(self)

    def to_json(self) -> dict[str, Any]:
        from transplanter.reverse.report import reverse_result_json

        return reverse_result_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.reverse.report import to_markdown

        return to_markdown(self, files)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """design.toml (``design_toml``); with whole teeth, the gear sheets, drawings.pdf, parts.csv and pitch-curve
        tables (``gear_files``) and, unless ``solids`` is False, the gears' STEP solids with the extra
        transplanter[cad] (``solid_files``)."""
        from transplanter.reverse.design_toml import write_design
        from transplanter.reverse.gear_files import write_gear_files
        from transplanter.reverse.solid_files import write_solids

        written = [write_design(self, folder)]
        if self.toothed is None:
            return written
        with progress.step("drawings"):
            written += write_gear_files(self.toothed, self.problem.direction, self.problem.title, Path(folder))
        if solids:
            with progress.step("solids"):
                written += write_solids(self.toothed, self.problem, Path(folder))
        return written

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.reverse.figures import figure_drawers

        return figure_drawers(self)

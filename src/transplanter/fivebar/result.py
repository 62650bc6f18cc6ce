"""A designed five-bar mechanism with its gear train, and the checks it passes."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from functools import cached_property
from pathlib import Path
from typing import TYPE_CHECKING, Any

from transplanter.command_result import CommandResult
from transplanter.fivebar.alternatives import Alternative, Failure
from transplanter.fivebar.band_search import PoseSetTrial
from transplanter.fivebar.candidate import Candidate
from transplanter.fivebar.key_pose_bands import PoseBands
from transplanter.fivebar.kinetostatics import Kinetostatics
from transplanter.fivebar.nlp import DesignSolution
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.region import Region
from transplanter.fivebar.shafts import ShaftDesign, design_shafts
from transplanter.fivebar.support import SupportDesign
from transplanter.fivebar.verification import Verification
from transplanter.tolerance import ToleranceAnalysis, ToleranceModel
from transplanter.trains.planetary import PlanetaryTrain
from transplanter.trains.pressure_angle import StagePressureAngles
from transplanter.trains.toothed_train import ToothedTrain

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer


@dataclass(frozen=True)
class FiveBarResult(CommandResult):
    """A five-bar mechanism designed for a ``FiveBarProblem``, with its planetary gear train.

    Attributes
    ----------
    problem : FiveBarProblem
        The problem solved (mm, radians), with the key poses the picked design chose where they were bands.
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
    pressure : StagePressureAngles
        The gear pressure angle of both meshes over the turn (``trains.pressure_angle``).
    loads : Kinetostatics
        Forces and torques over the turn for the planting load and the links' weights (``[load]``).
    pose_bands : PoseBands or None
        The key poses' bands as the problem gave them (None: all exact).
    band_trials : tuple of PoseSetTrial
        The pose sets the region was built for (``fivebar.band_search``): the bands' centres first.
    support : SupportDesign or None
        The seedling support timed to the design (``[support]``), else None.
    tolerance : ToleranceAnalysis or None
        How precise the built mechanism will be (``tolerance.analyse``), else None (``tolerance=False``).
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
    pressure: StagePressureAngles
    loads: Kinetostatics
    pose_bands: PoseBands | None = None
    band_trials: tuple[PoseSetTrial, ...] = ()
    support: SupportDesign | None = None
    tolerance: ToleranceAnalysis | None = None

    @property
    def source(self) -> str:
        return self.problem.source

    @property
    def train(self) -> PlanetaryTrain:
        """The pitch curves of the two gear stages and the correction factor k."""
        return self.toothed.train

    @cached_property
    def shafts(self) -> ShaftDesign:
        """Shaft and hinge-pin diameters and each gear's keyed bore (``fivebar.shafts``), worked out once."""
        return design_shafts(self.problem.shafts, self.toothed, self.loads, self.problem.solid_sizes.thickness_mm)

    @property
    def failures(self) -> list[str]:
        """Every check of the built mechanism it fails: verification, the gears' mesh and pressure angle, the
        support, then the gears' bores."""
        return [*self.verification.failures, *self.toothed.failures, *self.pressure.failures(),
                *(self.support.failures if self.support else []), *self.shafts.failures]

    def tolerance_model(self) -> ToleranceModel:
        """The built mechanism as a function of its manufactured dimensions (``fivebar.tolerance_model``)."""
        from transplanter.fivebar.tolerance_model import tolerance_model

        return tolerance_model(self)

    @property
    def chosen(self) -> Alternative:
        """The picked alternative."""
        return self.alternatives[self.picked - 1]

    def to_json(self) -> dict[str, Any]:
        from transplanter.fivebar.report import fivebar_result_json

        return fivebar_result_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.fivebar.report import to_markdown

        return to_markdown(self, files)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.fivebar.figures import figure_drawers

        return figure_drawers(self)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """``fivebar.write_files``: drawings, tables, the STEP solids unless ``solids`` is False and, unless
        ``animation`` is False, the animation."""
        from transplanter.fivebar.output_files import write_files

        return write_files(self, folder, animation=animation, solids=solids)

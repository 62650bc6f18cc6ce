"""A designed gear pair, and the checks it passes."""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from transplanter import progress
from transplanter.command_result import CommandResult
from transplanter.gears.composite_teeth import CompositeTeeth
from transplanter.gears.pair import GearPairDesign
from transplanter.gears.problem import GearProblem
from transplanter.gears.rack_teeth import ADDENDUM
from transplanter.gears.teeth import PairTeeth

if TYPE_CHECKING:
    from transplanter.figure_conventions import FigureDrawer


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


def _min_convex(rho, convexity) -> float | None:
    convex = convexity > 0
    return float(rho[convex].min()) if convex.any() else None


def _tooth_failures(teeth: PairTeeth | CompositeTeeth | None) -> list[str]:
    """Tooth outlines that cross themselves, or a composite pair's own checks."""
    if teeth is None:
        return []
    if isinstance(teeth, CompositeTeeth):          # composite teeth name their own crossings
        return list(teeth.failures)
    if not any(teeth.self_intersections):
        return []
    driver, driven = teeth.self_intersections
    return [f"tooth outlines cross themselves (driver {driver}, driven {driven} crossings): the cutter cuts "
            "away teeth it made, usually where a pitch curve bends sharper than the tooth; try fewer teeth "
            "(a larger pair.module), or pair.cutter = \"shaper\" for concave stretches"]


@dataclass(frozen=True)
class GearResult(CommandResult):
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
    teeth : PairTeeth, CompositeTeeth or None
        Tooth outlines (mm) when teeth are given; composite teeth for a driver with corners.
    ratio_correction : float or None
        Factor k that scaled a given ratio to close (Wang et al. 2025 eq 12).
    timings_s : dict
        Wall time of each stage (s).
    """

    problem: GearProblem
    design: GearPairDesign
    tooth_counts: ToothCounts | None
    teeth: PairTeeth | CompositeTeeth | None
    ratio_correction: float | None
    timings_s: dict

    @property
    def source(self) -> str:
        return self.problem.source

    @property
    def convex(self) -> list[bool]:
        """Whether each pitch curve (driver, driven) is convex all round."""
        return [bool((c > 0).all()) for c in self.design.convexity]

    @property
    def min_convex_curvature_radius(self) -> list[float | None]:
        """Smallest curvature radius of each pitch curve's convex stretches (mm; None when it has none)."""
        return [_min_convex(r, c) for r, c in zip(self.design.curvature_radius, self.design.convexity, strict=True)]

    @property
    def undercut(self) -> list[bool] | None:
        """Whether a rack of the module would undercut each gear: its smallest convex curvature radius below
        addendum * module / sin^2(pressure angle); None without a module."""
        if self.tooth_counts is None:
            return None
        limit = ADDENDUM * self.tooth_counts.module / np.sin(self.problem.pressure_angle) ** 2
        return [bool(v is not None and v < limit) for v in self.min_convex_curvature_radius]

    @property
    def failures(self) -> list[str]:
        """Checks the pair fails: tooth outlines that cross themselves (a cutter that cuts away teeth it
        made) cannot be made or drawn as given; composite teeth add their contact and mesh checks; a keyed bore
        that comes too close to the teeth (``gears.drawings.bore_failures``)."""
        from transplanter.gears.drawings import bore_failures

        return _tooth_failures(self.teeth) + bore_failures(self)

    def to_json(self) -> dict[str, Any]:
        from transplanter.gears.report import gear_result_json

        return gear_result_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.gears.report import to_markdown

        return to_markdown(self, files)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        from transplanter.gears.figures import figure_drawers

        return figure_drawers(self)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """The pitch curves and tooth outlines as CSV, SVG and DXF (``gears.write_drawings``), and the cut gears'
        STEP solids with the extra transplanter[cad] (``gears.solid_files``) unless ``solids`` is False."""
        from transplanter.gears.drawings import write_drawings
        from transplanter.gears.solid_files import write_solids

        with progress.step("drawings"):
            written = write_drawings(self, folder)
        if not solids:
            return written
        with progress.step("solids"):
            return written + write_solids(self, Path(folder), self.problem.solid_sizes)

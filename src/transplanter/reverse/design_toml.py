"""The design of a reverse run in a file: [arm] (pivot, carrier_length, arm_length, direction, branch) and
[train] (topology, split, peak_to_valley, center_distances, module, cutter, face_width_mm), under the names the
problem file and the report use. ``write_design`` writes a run's as design.toml; ``load_design`` reads one;
``evaluate_design`` makes the train for a problem's path with a design's arm and train, which reproduces the run
that wrote it."""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from transplanter.api_arguments import require_problem, require_switch
from transplanter.design_file import read_design_file, write_design_file
from transplanter.errors import ProblemError
from transplanter.reverse.arm_inverse import DIRECTION_NAMES
from transplanter.reverse.problem import ReverseProblem, read_arm, read_train
from transplanter.reverse.result import ReverseResult
from transplanter.reverse.synthesis import synthesize
from transplanter.solids.sizes import SolidSizes, read_solid_sizes
from transplanter.toml_fields import shown


@dataclass(frozen=True)
class ReverseDesign:
    """A reverse design: the arm and the train a path is made with (mm).

    Attributes
    ----------
    pivot : ndarray, shape (2,)
        The carrier center (mm).
    lengths : (float, float)
        Carrier and arm lengths (mm).
    direction : int
        +1 counterclockwise carrier, -1 clockwise.
    branch, topology, split : str
        As ``ReverseProblem``.
    peak_to_valley : float
        As ``ReverseProblem``.
    center_distances : (float, float) or None
        mm; None: half the carrier each (a four-gear train) or a three-gear train.
    module : float
        mm.
    cutter : str
        ``"rack"`` or ``"shaper"``.
    solid_sizes : SolidSizes
        The gears' face width (mm) for their STEP solids.
    source : str
        The design file.
    """

    pivot: np.ndarray
    lengths: tuple[float, float]
    direction: int
    branch: str
    topology: str
    split: str
    peak_to_valley: float
    center_distances: tuple[float, float] | None
    module: float
    cutter: str
    solid_sizes: SolidSizes
    source: str


def design_tables(result: ReverseResult) -> dict[str, dict[str, object]]:
    """[arm] and [train] of ``result``'s design, every number as the run used it."""
    problem, motion = result.problem, result.motion
    train: dict[str, object] = {"topology": problem.topology, "split": problem.split}
    if problem.split == "peak_to_valley":
        train["peak_to_valley"] = problem.peak_to_valley
    if problem.topology != "sun-idler-planet":
        halves = (motion.carrier_length / 2, motion.carrier_length / 2)
        chosen = result.toothed.train.center_distances if result.toothed else None
        train["center_distances"] = list(chosen or problem.center_distances or halves)
    train["module"] = problem.module
    train["cutter"] = problem.cutter
    train["face_width_mm"] = problem.solid_sizes.face_width(problem.module)
    return {"arm": {"pivot": problem.pivot.tolist(), "carrier_length": motion.carrier_length,
                    "arm_length": motion.arm_length, "direction": DIRECTION_NAMES[problem.direction],
                    "branch": problem.branch},
            "train": train}


def write_design(result: ReverseResult, folder: str | Path) -> Path:
    """``folder/design.toml`` of ``result``; the path written."""
    problem = result.problem
    return write_design_file(
        folder, "The reverse design made by transplanter reverse",
        f"Made for {problem.title or problem.source}. Make it again with: transplanter reverse {problem.source} "
        "--design design.toml", design_tables(result))


def load_design(path: str | Path) -> ReverseDesign:
    """Read a design file (TOML, mm): [arm] with both lengths, and [train], as in a problem file. A bad field
    raises ProblemError (``read_design_file``)."""
    data, arm, read = read_design_file(path, {"arm", "train"}, "arm",
                                       {"pivot", "carrier_length", "arm_length", "direction", "branch"})
    if "carrier_length" not in arm and "arm_length" not in arm:
        read.fail("arm.carrier_length", None, "the carrier and arm lengths of the design (mm)")
    pivot, lengths, direction, branch = read_arm(read, arm)
    assert lengths is not None          # read_arm takes both lengths or neither
    topology, split, coefficient, centers, module, cutter = read_train(read, data.get("train", {}))
    return ReverseDesign(pivot, lengths, direction, branch, topology, split, coefficient, centers, module, cutter,
                         read_solid_sizes(read, data.get("train", {}), "train"), str(path))


def evaluate_design(problem: ReverseProblem, design: ReverseDesign, tolerance: bool = True) -> ReverseResult:
    """The train for ``problem``'s path with ``design``'s arm and train (``synthesize``, with the tolerance analysis
    unless ``tolerance`` is False)."""
    require_problem(problem, ReverseProblem, "reverse")
    require_switch("tolerance", tolerance)
    if not isinstance(design, ReverseDesign):
        raise ProblemError(f"design = {shown(design)!r}: expected a ReverseDesign (from "
                           "transplanter.reverse.load_design(path))")
    fields = {field.name: getattr(design, field.name) for field in dataclasses.fields(design) if field.name != "source"}
    return synthesize(dataclasses.replace(problem, points=problem.points + problem.pivot - design.pivot, **fields),
                      tolerance)

"""Evaluating a given five-bar design (Wang et al. 2025 Table 4 style) against a problem.

A design gives the carrier O-A (length, angle in pose 1), connecting rod I A-F (length,
angle in pose 1), |EP|, the receiving plate B-E and hinge B, under the names of the report's design
table (``carrier_length_OA``, ``rod_length_AF``, ``push_plate_EP``, ``receiving_plate_length_BE``,
``hinge_B``, ``hinge_E``). E is where the circles about B and P1 meet: two assemblies, both judged (or
the one nearest ``hinge_E``).

Without a motion (a published design), per key pose the carrier stands at its phase and the rod's
relative angle is the one that brings P closest to the key pose (what the best gear could do).
Reported: that position error of P, the plate-angle error there, and, with the plate placed exactly,
how far each chain misses (|BE| - L4, |AF| - L2). The whole-turn conditions come from
``evaluate_candidate`` with the relative angle fitted through the key and return points, as in the
paper. With a motion (``[relative_angle]``, as design.toml of a run gives it: the gears' rho(c)), the
key poses and the whole turn are judged with that motion (``given_motion``). With ``[support]``, the
seedling support is timed to the motion.

The ranges of a given design are checked with a slack of ``RANGE_TOLERANCE`` times the problem's reach
(the largest distance of a key pose or return point from O), so a design rounded to 0.01 mm that
sits on a range's end is not failed by the last bits of its arithmetic.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from transplanter import progress
from transplanter.api_arguments import require_problem
from transplanter.command_result import CommandResult
from transplanter.design_file import read_design_file, renamed_fields
from transplanter.errors import ProblemError
from transplanter.fivebar.candidate import Candidate, evaluate_candidate
from transplanter.fivebar.given_motion import judge_motion, pose_errors
from transplanter.fivebar.key_pose_bands import QUANTITIES, PoseBands
from transplanter.fivebar.linkage import FiveBar, circle_intersection, from_hinges
from transplanter.fivebar.nlp import reach
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.fivebar.support import SupportDesign, design_support
from transplanter.toml_fields import ClassFields, FieldReader, shown

#: The fields of [design], as design.toml of a run writes them from the report's design table: lengths (mm),
#: angles (deg) and the hinges B and E in pose 1 (mm).
DESIGN_FIELDS = ("carrier_length_OA", "carrier_angle_deg", "rod_length_AF", "rod_angle_deg", "push_plate_EP",
                 "receiving_plate_length_BE", "hinge_B", "hinge_E")
_FIELDS = DESIGN_FIELDS[:6]
_LENGTHS = tuple(key for key in _FIELDS if not key.endswith("_deg"))
#: Names a design file had before they were the report's (read with a note).
RENAMED = {"carrier_length": "carrier_length_OA", "rod_length": "rod_length_AF",
           "push_plate_length": "push_plate_EP", "receiving_plate_length": "receiving_plate_length_BE",
           "hinge_b": "hinge_B", "hinge_e": "hinge_E"}
#: Slack of the [ranges] checks of a given design, per mm of the problem's reach.
RANGE_TOLERANCE = 1e-9


@dataclass(frozen=True)
class GivenDesign:
    """A given five-bar design (Wang et al. 2025 Table 4 style), in mm and radians.

    Attributes
    ----------
    carrier_length_OA, rod_length_AF : float
        |OA| and |AF| (mm).
    carrier_angle, rod_angle : float
        Directions of O->A and A->F in pose 1 (rad, counterclockwise from +x).
    push_plate_EP, receiving_plate_length_BE : float
        |EP| and |BE| (mm).
    hinge_B : ndarray, shape (2,)
        Fixed hinge B (mm).
    hinge_E : ndarray or None
        Hinge E in pose 1 (mm), picks the assembly; None: the assembly nearest the key poses.
    source : str
        The design file.
    relative_angle : RelativeAngle or None
        The motion rho(c) the gears make (rad), or None: the motion is fitted (module docstring).
    return_point_turns : ndarray or None
        Carrier turns (rad) at the return points, given with ``relative_angle``.
    key_poses : ndarray, shape (4, 4), or None
        The key poses the design meets, rows x, y (mm), plate direction, carrier turn (rad): the ones a design
        chose inside a problem's bands; None: the problem's.
    """

    carrier_length_OA: float
    carrier_angle: float
    rod_length_AF: float
    rod_angle: float
    push_plate_EP: float
    receiving_plate_length_BE: float
    hinge_B: np.ndarray
    hinge_E: np.ndarray | None
    source: str
    relative_angle: RelativeAngle | None = None
    return_point_turns: np.ndarray | None = None
    key_poses: np.ndarray | None = None

    def __post_init__(self):
        check = ClassFields(self)
        for name in _LENGTHS:
            check.positive(name)
        for name in ("carrier_angle", "rod_angle"):
            check.number(name, -2 * np.pi, 2 * np.pi, "an angle within one turn of zero (rad)")
        check.array("hinge_B", (2,))
        if self.hinge_E is not None:
            check.array("hinge_E", (2,))
        if self.key_poses is not None:
            check.array("key_poses", (4, 4))
        if (self.relative_angle is None) != (self.return_point_turns is None):
            check.fail("return_point_turns", self.return_point_turns, "given together with relative_angle")
        check.text("source")


@dataclass(frozen=True)
class DesignEvaluation(CommandResult):
    """How well a given design meets a five-bar problem.

    Attributes
    ----------
    problem : FiveBarProblem
        The problem the design is judged against.
    design : GivenDesign
        The design as given.
    mech : FiveBar
        The assembled mechanism (the assembly picked).
    candidate : Candidate
        Whole-turn conditions with the relative angle fitted through the key and return points.
    position_errors_mm : ndarray, shape (4,)
        Closest distance of P to each key pose over the rod's relative angle (mm).
    angle_errors_deg : ndarray, shape (4,)
        Plate-angle error there (deg).
    chain_errors_mm : (ndarray, ndarray)
        |BE| - L4 and |AF| - L2 at each key pose with the plate placed exactly (mm).
    alternatives : list of float
        Worst position error of each assembly tried (mm).
    support : SupportDesign or None
        The seedling support timed to the design (``[support]``), else None.
    """

    problem: FiveBarProblem
    design: GivenDesign
    mech: FiveBar
    candidate: Candidate
    position_errors_mm: np.ndarray
    angle_errors_deg: np.ndarray
    chain_errors_mm: tuple[np.ndarray, np.ndarray]
    alternatives: list[float]
    support: SupportDesign | None = None

    @property
    def source(self) -> str:
        """The design file (the report is about it)."""
        return self.design.source

    @property
    def relative_angle_monotonic(self) -> bool:
        """Whether the relative angle fitted through the key and return points increases all round."""
        candidate = self.candidate
        return candidate.relative_angle is not None and "monotonic" not in " ".join(candidate.defects)

    @property
    def failures(self) -> list[str]:
        """The conditions the design violates (``Candidate.defects``), then the support's failures."""
        return [*self.candidate.failures, *(self.support.failures if self.support else [])]

    def to_json(self) -> dict[str, Any]:
        from transplanter.fivebar.report import design_evaluation_json

        return design_evaluation_json(self)

    def to_markdown(self, files: Sequence[str] = ()) -> str:
        from transplanter.fivebar.report import evaluation_markdown

        return evaluation_markdown(self)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """The support cam's drawings (``cam.write_drawings``), with ``[support]``."""
        if self.support is None:
            return []
        from transplanter.cam.drawings import write_drawings

        with progress.step("drawings"):
            return write_drawings(self.support.cam, folder)


def load_design(path: str | Path) -> GivenDesign:
    """Read a design file (TOML, mm and degrees): a table [design] with carrier_length_OA,
    carrier_angle_deg, rod_length_AF, rod_angle_deg, push_plate_EP, receiving_plate_length_BE,
    hinge_B = [x, y] and optionally hinge_E = [x, y] (the report's names; the older names of ``RENAMED``
    are read with a one-line note); optionally the motion, a table [relative_angle] with rho1_deg,
    control_values_deg and return_point_turns_deg as the report gives them (design.toml of a run); and, for a
    problem with key-pose bands, the poses the design chose, a table [key_poses] with four each of x, y (mm),
    angle_deg and carrier_turn_deg. A bad field raises ProblemError (``read_design_file``).
    """
    data, table, read = read_design_file(path, {"design", "relative_angle", "key_poses"}, "design",
                                         {*DESIGN_FIELDS, *RENAMED})
    table = renamed_fields(read, table, "design", RENAMED)
    values = {key: read.number(table, key, "design") for key in _FIELDS}
    for key in _LENGTHS:
        if values[key] <= 0:
            read.fail(f"design.{key}", values[key], "a positive length (mm)")
    if "hinge_B" not in table:
        read.fail("design.hinge_B", None, "the fixed hinge B = [x, y] (mm)")
    hinge_e = read.point(table["hinge_E"], "design.hinge_E") if "hinge_E" in table else None
    relative, return_turns = _read_motion(read, data["relative_angle"]) if "relative_angle" in data else (None, None)
    poses = _read_key_poses(read, data["key_poses"]) if "key_poses" in data else None
    return GivenDesign(values["carrier_length_OA"], np.radians(values["carrier_angle_deg"]), values["rod_length_AF"],
                       np.radians(values["rod_angle_deg"]), values["push_plate_EP"],
                       values["receiving_plate_length_BE"], read.point(table["hinge_B"], "design.hinge_B"), hinge_e,
                       str(path), relative, return_turns, poses)


def _read_key_poses(read: FieldReader, table) -> np.ndarray:
    """[key_poses]: four each of x, y (mm), angle_deg and carrier_turn_deg -> rows x, y, direction, turn (mm, rad)."""
    read.keys(table, set(QUANTITIES), "key_poses")
    columns = []
    for quantity in QUANTITIES:
        values = read.numbers(table, quantity, "key_poses", minimum_count=4)
        if len(values) != 4:
            read.fail(f"key_poses.{quantity}", table[quantity], "four values, one per key pose")
        columns.append(np.radians(values) if quantity.endswith("_deg") else values)
    return np.column_stack(columns)


def _read_motion(read: FieldReader, table) -> tuple[RelativeAngle, np.ndarray]:
    """[relative_angle]: rho1_deg, control_values_deg (at least 4) and return_point_turns_deg -> the motion (rad)
    and the carrier turns at the return points (rad)."""
    read.keys(table, {"rho1_deg", "control_values_deg", "return_point_turns_deg"}, "relative_angle")
    rho1 = read.number(table, "rho1_deg", "relative_angle")
    control = read.numbers(table, "control_values_deg", "relative_angle", minimum_count=4)
    turns = read.numbers(table, "return_point_turns_deg", "relative_angle")
    return RelativeAngle(float(np.radians(rho1)), np.radians(control)), np.radians(turns)


def _poses_outside(problem: FiveBarProblem, chosen: np.ndarray, slack: float) -> list[str]:
    """Where chosen key poses (4, 4) leave the problem's bands (its exact poses where it has none) by more than
    ``slack`` (mm) in x and y, ``RANGE_TOLERANCE`` (rad) in angle and carrier turn."""
    exact = np.c_[problem.poses, problem.carrier_turns]
    bands = problem.pose_bands or PoseBands(exact, exact)
    per_column = np.array([slack, slack, RANGE_TOLERANCE, RANGE_TOLERANCE])
    return [f"{bands.field(problem.labels, i, q)}: the design's key pose is outside the problem's band"
            for i, q in bands.outside(chosen, per_column)]


def _closest_pose(mech: FiveBar, pose: np.ndarray, turn: float) -> tuple[float, float]:
    """Smallest |P - P_i| over the rod's relative angle at carrier turn ``turn``, and the plate-angle error there."""
    centre = float(mech.relative_angle_at(pose, turn))
    for width in (np.radians(10.0), np.radians(0.02), np.radians(4e-5)):
        rho = centre + np.linspace(-width, width, 2001)
        state = mech.forward(np.full_like(rho, turn), rho)
        distance = np.linalg.norm(state["p"] - pose[:2], axis=1)
        k = int(np.nanargmin(distance))
        centre = rho[k]
    return float(distance[k]), float(np.degrees(np.angle(np.exp(1j * (state["direction"][k] - pose[2])))))


def evaluate_design(problem: FiveBarProblem, design: GivenDesign) -> DesignEvaluation:
    """Judge a given design against a problem's key poses and whole-turn conditions.

    Parameters
    ----------
    problem : FiveBarProblem
        The problem (mm, radians).
    design : GivenDesign
        From ``load_design``.

    Returns
    -------
    DesignEvaluation
        Errors at the key poses (mm, deg), chain errors (mm) and the conditions violated.

    Raises
    ------
    ProblemError
        When the plate cannot reach pose 1 (no assembly), or the arguments are not a problem and a design.
    """
    require_problem(problem, FiveBarProblem, "fivebar")
    if not isinstance(design, GivenDesign):
        raise ProblemError(f"design = {shown(design)!r}: expected a GivenDesign (from "
                           "transplanter.fivebar.load_design(path))")
    slack = RANGE_TOLERANCE * reach(problem)
    outside = _poses_outside(problem, design.key_poses, slack) if design.key_poses is not None else []
    if design.key_poses is not None:
        problem = problem.with_poses(design.key_poses[:, :3], design.key_poses[:, 3])
    a1 = design.carrier_length_OA * np.array([np.cos(design.carrier_angle), np.sin(design.carrier_angle)])
    f1 = a1 + design.rod_length_AF * np.array([np.cos(design.rod_angle), np.sin(design.rod_angle)])
    relative = design.relative_angle
    options: list[tuple[np.ndarray, FiveBar, np.ndarray]] = []
    for side in (1.0, -1.0):
        e1, margin = circle_intersection(design.hinge_B, design.receiving_plate_length_BE, problem.poses[0, :2],
                                         design.push_plate_EP, side)
        if margin < 0:
            continue
        mech = from_hinges(problem.poses[0], design.hinge_B, e1, a1, f1)
        errors = (np.c_[pose_errors(mech, relative, problem.poses, problem.carrier_turns)] if relative is not None
                  else np.array([_closest_pose(mech, pose, turn)
                                 for pose, turn in zip(problem.poses, problem.carrier_turns, strict=True)]))
        options.append((e1, mech, errors))
    if not options:
        gap = np.linalg.norm(design.hinge_B - problem.poses[0, :2])
        FieldReader(design.source).fail(
            "design.push_plate_EP", design.push_plate_EP,
            f"a plate that reaches: |B P1| = {gap:.3f} mm cannot be spanned by BE = "
            f"{design.receiving_plate_length_BE:g} and EP = {design.push_plate_EP:g}")
    worst = [float(np.nanmax(option[2][:, 0])) for option in options]
    if design.hinge_E is not None:
        pick = int(np.argmin([np.linalg.norm(o[0] - design.hinge_E) for o in options]))
    else:
        pick = int(np.argmin(worst))
    _, mech, errors = options[pick]
    if relative is not None and design.return_point_turns is not None:
        if len(design.return_point_turns) != len(problem.return_points):
            FieldReader(design.source).fail(
                "relative_angle.return_point_turns_deg", np.degrees(design.return_point_turns).tolist(),
                f"one carrier turn per return point of {problem.source} ({len(problem.return_points)})")
        candidate = judge_motion(problem, mech, relative, design.return_point_turns, slack)
    else:
        candidate = evaluate_candidate(problem, mech, range_slack=slack)
    if outside:
        candidate = dataclasses.replace(candidate, defects=[*outside, *candidate.defects])
    support = None
    if problem.support is not None:
        if candidate.relative_angle is None:
            raise ProblemError(f"{problem.source}: [support] needs the design's motion over a turn, which "
                               f"{design.source} does not give: {'; '.join(candidate.defects)}")
        assert candidate.stroke is not None     # a candidate with a relative angle has its return stroke
        support = design_support(problem.support, mech, candidate.relative_angle, problem.carrier_turns,
                                 candidate.stroke.carrier_turns, problem.source)
    return DesignEvaluation(problem, design, mech, candidate, errors[:, 0], errors[:, 1],
                            mech.joint_chain_errors(problem.poses, problem.carrier_turns), worst, support)

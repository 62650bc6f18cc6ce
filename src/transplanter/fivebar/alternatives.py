"""Every feasible region candidate refined, each result judged by its own forward evaluation,
the same mechanisms merged, and the alternatives ranked.

The design NLP is a black box here: a refined design is evaluated again on its own by
``FiveBar.forward`` over a fine grid of the carrier turn, ``range_values`` and
``RelativeAngle.evaluate``, at the key poses the design chose. That gives the transmission angle at
E, the closure angle EBF, the ratio range, the return-point misses and the values of the bounds the
NLP found it on, and it rejects a design that breaks a condition, a band or a requirement (the
candidate is then listed as failed, with the reason).

Ranking rule (``rank``): the largest smallest transmission angle at E over the turn first.
Angles within ``ANGLE_TIE`` (relative) of the first of their group tie; a tie goes to the
smaller largest return-point miss (misses within ``MISS_TIE`` of the reach tie), then to the
gentler ratio, i.e. the smaller spread i0_max / i0_min; then to the earlier start candidate.
"""
from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from transplanter.errors import SolverError, TransplanterError
from transplanter.fivebar.candidate import (
    GRID,
    Candidate,
    closure_defect,
    monotonic_defect,
    range_defect,
    range_values,
    ratio_defect,
)
from transplanter.fivebar.design_solver import DesignSolver, HollowError, concavity_text
from transplanter.fivebar.lanes import refine_in_lanes
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.nlp import PRESSURE_LIMIT, RETURN_TOLERANCE, DesignSolution, reach
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import ratio_range
from transplanter.fivebar.return_passes import other_passes
from transplanter.fivebar.whole_turn import CURVES
from transplanter.geometry.planar import TWO_PI
from transplanter.trains.pressure_angle import stage_pressure_angles
from transplanter.trains.toothed_train import TrainSize, train_size

#: Carrier turns of the evaluation (0.1 deg apart).
TURN_SAMPLES = 3600
#: A bound is active when the design is within this fraction of the bound's own scale (range width,
#: margin floor, span of the ratio bounds) of it; beyond it on the wrong side, the design fails.
ACTIVE_TOLERANCE = 1e-4
#: Key poses must be met to this fraction of the reach (positions) and in radians (plate angles).
KEY_TOLERANCE = 1e-8
#: Two designs are one mechanism when lengths agree to this fraction of the reach and angles, the
#: relative angle included, to this many radians. Starts that reach one optimum hold it on different
#: exchange grids, so they agree only to the exchange's tolerances (7e-6 on the bundled example).
MERGE_TOLERANCE = 1e-4
#: Smallest angles EBF within this fraction of each other rank as a tie.
ANGLE_TIE = 1e-3
#: Largest return-point misses within this fraction of the reach rank as a tie.
MISS_TIE = 1e-6

#: The ranking rule in words (the reports state it).
RANKING_RULE = (f"Ranked by the smallest transmission angle at E (between EF and BE) over the turn, largest first; "
                f"angles within "
                f"{ANGLE_TIE:.1%} of each other tie, and a tie goes to the smaller largest return-point miss "
                f"(misses within {MISS_TIE:g} of the reach, the farthest key pose or return point from O, tie), "
                f"then to the gentler ratio (smaller i0 max / min), then to the earlier start candidate.")

#: ``progress(step, done, total)``: called with done = 0 when a step starts and after each unit of it.
Progress = Callable[[str, int, int], None]


@dataclass(frozen=True)
class ActiveBound:
    """A bound the design sits on: ``name`` as the problem file names it (``ranges.ep``,
    ``min_closure_margin``, ``ratio``, ``key_poses.P2.angle_deg``, ``requirements.min_stroke_mm``, ...),
    ``side`` (``lower`` or ``upper``), the bound's ``limit`` and the design's ``value``, both in the
    file's units (mm, deg; a margin or a ratio as it is)."""

    name: str
    side: str
    limit: float
    value: float

    def __str__(self) -> str:
        return f"{self.name} {'>=' if self.side == 'lower' else '<='} {self.limit:g}"


@dataclass(frozen=True, eq=False)
class Alternative:
    """A refined design with its independent evaluation (mm, radians).

    Attributes
    ----------
    design : DesignSolution
        The NLP's result from the first of ``starts``.
    starts : tuple of int
        Indices into ``region.feasible`` of every candidate the NLP took to this mechanism.
    transmission_angle, transmission_turn : float
        Smallest transmission angle at E over the turn (between EF and BE, folded to [0, pi/2]: the
        angle that carries the load) and the carrier turn where it occurs.
    closure_angle, closure_turn : float
        Smallest angle EBF over the turn (folded likewise; its sin^2 is eq 10's margin without
        scale: 0 where the chain jams), and where.
    ratio_range : (float, float)
        Smallest and largest total ratio i0 = 1 / rho'.
    return_misses_mm : ndarray, shape (m,)
        Distance of P from each return point at the carrier turn the design passes it.
    min_closure_margin : float
        Smallest sin^2(EBF) over the turn.
    active_bounds : tuple of ActiveBound
    gears : TrainSize or str or None
        Whole-tooth sizes of its train (``trains.toothed_train.train_size``), or why there are none;
        None until ``with_gear_sizes``.
    restroke : str
        How the design was reached from its starts' own optimum when a return point was moved to another
        pass of P (``_other_strokes``); empty when it was not.
    """

    design: DesignSolution
    starts: tuple[int, ...]
    transmission_angle: float
    transmission_turn: float
    closure_angle: float
    closure_turn: float
    ratio_range: tuple[float, float]
    return_misses_mm: np.ndarray
    min_closure_margin: float
    active_bounds: tuple[ActiveBound, ...]
    gears: TrainSize | str | None = None
    restroke: str = ""

    @property
    def largest_miss_mm(self) -> float:
        return float(self.return_misses_mm.max())

    @property
    def ratio_spread(self) -> float:
        """i0_max / i0_min: 1 for a constant ratio (circular gears), larger for harsher gears."""
        return self.ratio_range[1] / self.ratio_range[0]


@dataclass(frozen=True)
class Failure:
    """A feasible region candidate (index into ``region.feasible``) whose refinement failed, and why;
    ``held``: IPOPT failed with the pitch curves held to shaper hollows (``DesignSolver.without_hold``)."""

    start: int
    reason: str
    held: bool = False


def _folded_angle(u: np.ndarray, v: np.ndarray) -> np.ndarray:
    """Angle between vectors u and v (..., 2) folded to [0, pi/2]: 0 when they are collinear."""
    cross = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    return np.arctan2(np.abs(cross), np.abs(np.sum(u * v, axis=-1)))


def transmission_angles(mech: FiveBar, state: dict) -> tuple[np.ndarray, np.ndarray]:
    """The transmission angle at E (between EF and BE) and the closure angle EBF at B (rad, folded to
    [0, pi/2]) for the hinge positions of ``FiveBar.forward``'s ``state``."""
    e, f = state["e"], state["f"]
    return _folded_angle(f - e, mech.hinge_b - e), _folded_angle(e - mech.hinge_b, f - mech.hinge_b)


def _requirement_values(problem: FiveBarProblem, poses: np.ndarray):
    """Per requirement name, ((limit, value) on its lower side, (limit, value) on its upper side): the value
    nearest that side among the requirement's rows, for the chosen key poses (mm)."""
    rows = problem.requirements.rows(list(poses[:, 0]), list(poses[:, 1]), problem.stroke_direction)
    for name in dict.fromkeys(row[0] for row in rows):
        mine = [row for row in rows if row[0] == name]
        lower = min(mine, key=lambda row: row[1] - row[2])
        upper = min(mine, key=lambda row: row[3] - row[1])
        yield name, ((float(lower[2]), float(lower[1])), (float(upper[3]), float(upper[1])))


def active_bounds(problem: FiveBarProblem, design: DesignSolution, min_margin: float,
                  ratios: tuple[float, float], misses: np.ndarray, transmission_angle_deg: float = float("nan"),
                  pressure_angle_deg: float = float("nan")) -> tuple[ActiveBound, ...]:
    """The bounds the design NLP found its solution on (``DesignSolution.active_bounds``, decided by the
    ``solve`` layer), each with the problem's limit and the value of the design's own evaluation (mm,
    margin, ratio, a kappa): ``[ranges]``, the margin floor, the ratio bounds, the return tolerance (with
    the return points on it; every point when the tolerance is 0), the pitch curves' curvature floor, the
    key poses' band edges, the relative requirements and the transmission angle's floor."""
    resolved = problem.with_poses(design.poses, design.carrier_turns)
    values = range_values(resolved, design.mech)
    chosen = np.c_[design.poses, design.carrier_turns]
    in_file_units = np.array([1.0, 1.0, 180 / np.pi, 180 / np.pi])
    bands = problem.pose_bands
    banded = {} if bands is None else {bands.field(problem.labels, int(i), int(q)): (int(i), int(q))
                                       for i, q in zip(*np.nonzero(bands.banded), strict=True)}
    requirement_values = dict(_requirement_values(problem, design.poses))
    found = []
    on_tolerance = [j for j in range(len(problem.return_points)) if problem.return_tolerance_mm == 0] or [
        j for bound in design.active_bounds if bound.name == RETURN_TOLERANCE for j in bound.entries]
    for bound in design.active_bounds:
        side = ("lower", "upper").index(bound.side)
        if bound.name.startswith("ranges."):
            key = bound.name.removeprefix("ranges.")
            found.append(ActiveBound(bound.name, bound.side, problem.ranges[key][side], float(values[key])))
        elif bound.name == "min_closure_margin":
            found.append(ActiveBound(bound.name, bound.side, problem.min_closure_margin, min_margin))
        elif bound.name == "ratio":
            found.append(ActiveBound(bound.name, bound.side, problem.ratio_bounds[side], ratios[side]))
        elif bound.name.startswith("a kappa of the"):
            curve = CURVES.index(bound.name.removeprefix("a kappa of the ").removesuffix(" pitch curve"))
            floor = design.curvature_floor
            assert floor is not None, "a kappa is reported active only where the rows held it"
            found.append(ActiveBound(bound.name, bound.side, floor, design.min_curvature[curve]))
        elif bound.name in banded and bands is not None:
            i, q = banded[bound.name]
            limit = (bands.low if side == 0 else bands.high)[i, q] * in_file_units[q]
            found.append(ActiveBound(bound.name, bound.side, float(limit), float(chosen[i, q] * in_file_units[q])))
        elif bound.name in requirement_values:
            limit, value = requirement_values[bound.name][side]
            found.append(ActiveBound(bound.name, bound.side, limit, value))
        elif bound.name == PRESSURE_LIMIT:
            found.append(ActiveBound(bound.name, bound.side, float(np.degrees(problem.gearing.max_pressure_angle)),
                                     pressure_angle_deg))
        elif bound.name == "conditions.min_transmission_angle_deg" and problem.min_transmission_angle is not None:
            found.append(ActiveBound(bound.name, bound.side, float(np.degrees(problem.min_transmission_angle)),
                                     transmission_angle_deg))
    if on_tolerance:
        points = f"return point{'s' * (len(on_tolerance) > 1)} {', '.join(str(j + 1) for j in on_tolerance)}"
        found.append(ActiveBound(f"{RETURN_TOLERANCE} ({points})", "upper", problem.return_tolerance_mm,
                                 float(misses[on_tolerance].max())))
    order = ("key_poses.", "requirements.", "ranges.", "conditions.min_transmission_angle_deg", "min_closure_margin",
             "ratio", RETURN_TOLERANCE, PRESSURE_LIMIT, "a kappa of the")
    return tuple(sorted(found, key=lambda b: next(k for k, head in enumerate(order) if b.name.startswith(head))))


def _defects(problem: FiveBarProblem, design: DesignSolution, slope: np.ndarray,
             ratios: tuple[float, float], min_margin: float) -> list[str]:
    """The conditions the refined design breaks beyond ``ACTIVE_TOLERANCE`` (empty: none)."""
    mech, relative = design.mech, design.relative_angle
    key = mech.forward(problem.carrier_turns, relative.evaluate(problem.carrier_turns))
    position = np.linalg.norm(key["p"] - problem.poses[:, :2], axis=1)
    angle = np.abs(np.angle(np.exp(1j * (key["direction"] - problem.poses[:, 2]))))
    defects = []
    if not (np.all(position <= KEY_TOLERANCE * reach(problem)) and np.all(angle <= KEY_TOLERANCE)):
        defects.append(f"key poses: missed by up to {np.max(position):.3g} mm and "
                       f"{np.degrees(np.max(angle)):.3g} deg")
    floor = problem.min_closure_margin
    if not min_margin >= floor * (1 - ACTIVE_TOLERANCE):      # NaN: the chain does not close somewhere
        defects.append(closure_defect(min_margin, floor))
    if slope.min() <= 0:
        defects.append(monotonic_defect(relative.evaluate(GRID, 1)))
    else:
        low, high = problem.ratio_bounds
        slack = ACTIVE_TOLERANCE * (high - low)
        if ratios[0] < low - slack or ratios[1] > high + slack:
            defects.append(ratio_defect(*ratios, problem.ratio_bounds))
    values = range_values(problem, mech)
    for name, (low, high) in problem.ranges.items():
        if not low - ACTIVE_TOLERANCE * (high - low) <= values[name] <= high + ACTIVE_TOLERANCE * (high - low):
            defects.append(range_defect(name, float(values[name]), (low, high)))
    return defects


def _chosen_pose_defects(problem: FiveBarProblem, design: DesignSolution) -> list[str]:
    """The bands and requirements the design's chosen key poses break beyond ``ACTIVE_TOLERANCE`` (of the band's
    width, of the reach)."""
    defects = []
    bands = problem.pose_bands
    if bands is not None:
        chosen = np.c_[design.poses, design.carrier_turns]
        for i, q in bands.outside(chosen, ACTIVE_TOLERANCE * (bands.high - bands.low)):
            defects.append(f"{bands.field(problem.labels, i, q)}: chosen outside its band")
    broken = problem.requirements.broken(design.poses, problem.stroke_direction, ACTIVE_TOLERANCE * reach(problem))
    return defects + [f"{name}: not met by the chosen key poses" for name in broken]


def assess(problem: FiveBarProblem, design: DesignSolution, start: int) -> Alternative | Failure:
    """The refined design from ``region.feasible[start]`` evaluated on its own at the key poses it chose: an
    ``Alternative``, or a ``Failure`` naming every condition, band or requirement it breaks."""
    mech, relative = design.mech, design.relative_angle
    resolved = problem.with_poses(design.poses, design.carrier_turns)
    turns = np.linspace(0, TWO_PI, TURN_SAMPLES, endpoint=False)
    state = mech.forward(turns, relative.evaluate(turns))
    slope = relative.evaluate(turns, 1)
    ratios = ratio_range(slope)
    min_margin = float(np.min(state["margin"]))
    pressure = stage_pressure_angles(relative, design.correction, problem.gearing, turns)
    defects = [*_defects(resolved, design, slope, ratios, min_margin), *_chosen_pose_defects(problem, design),
               *pressure.failures()]
    if defects:
        return Failure(start, "; ".join(defects))
    at_e, at_b = transmission_angles(mech, state)
    returns = mech.forward(design.stroke.carrier_turns, relative.evaluate(design.stroke.carrier_turns))
    misses = np.linalg.norm(returns["p"] - problem.return_points, axis=1)
    return Alternative(design, (start,), float(at_e.min()), float(turns[at_e.argmin()]), float(at_b.min()),
                       float(turns[at_b.argmin()]), ratios, misses, min_margin,
                       active_bounds(problem, design, min_margin, ratios, misses, float(np.degrees(at_e.min())),
                                     float(np.degrees(pressure.largest.max()))))


def mechanism_signature(design: DesignSolution, size: float) -> np.ndarray:
    """Lengths in units of ``size``, angles in radians, and the relative angle at 36 turns: what
    makes two designs one mechanism."""
    mech = design.mech
    lengths = np.r_[mech.carrier_length, mech.rod_length, mech.hinge_b, mech.receiving_length, mech.e_local,
                    mech.f_local] / size
    return np.r_[lengths, mech.carrier_angle, mech.branch, design.relative_angle.evaluate(GRID[::20])]


def merge(alternatives: list[Alternative], size: float) -> list[Alternative]:
    """One alternative per mechanism (``MERGE_TOLERANCE``), kept from its first start and listing every start."""
    merged: list[Alternative] = []
    signatures: list[np.ndarray] = []
    for alternative in alternatives:
        signature = mechanism_signature(alternative.design, size)
        same = [k for k, other in enumerate(signatures) if np.abs(signature - other).max() <= MERGE_TOLERANCE]
        if same:
            first = merged[same[0]]
            merged[same[0]] = replace(first, starts=first.starts + alternative.starts)
        else:
            merged.append(alternative)
            signatures.append(signature)
    return merged


def _tiered(items: list, keys: list) -> list:
    """``items`` in ascending order of the first key; a run of items within that key's tolerance of the
    run's first item is ordered by the remaining keys (a stable sort: ties keep their order)."""
    if not keys or len(items) < 2:
        return list(items)
    (value, tolerance), rest = keys[0], keys[1:]
    remaining, ordered = sorted(items, key=value), []
    while remaining:
        lead = value(remaining[0])
        count = sum(value(item) - lead <= tolerance(lead) for item in remaining)
        ordered += _tiered(remaining[:count], rest)
        remaining = remaining[count:]
    return ordered


def rank(alternatives: list[Alternative], size: float) -> list[Alternative]:
    """The alternatives best first by the rule of the module docstring (``size``: the reach, mm)."""
    keys = [(lambda a: -a.transmission_angle, lambda lead: ANGLE_TIE * abs(lead)),
            (lambda a: a.largest_miss_mm, lambda lead: MISS_TIE * size),
            (lambda a: a.ratio_spread, lambda lead: 0.0)]
    return _tiered(sorted(alternatives, key=lambda a: a.starts[0]), keys)


def refine_all(problem: FiveBarProblem, solver: DesignSolver, candidates: list[Candidate],
               progress: Progress | None = None) -> tuple[list[Alternative], list[Failure], list[float]]:
    """Refine every candidate in the fixed lanes of ``fivebar.lanes``, lane 0 on ``solver`` (built for
    ``problem``); the ranked, merged alternatives, the failures (by start; where every start failed, each
    held one with ``DesignSolver.without_hold``'s numbers), and the wall time of each refinement (s)."""
    outcomes: list[Alternative | Failure | None] = [None] * len(candidates)
    seconds = [0.0] * len(candidates)

    def refine(lane_solver: DesignSolver, index: int) -> Alternative | Failure:
        try:
            return assess(problem, lane_solver.refine(candidates[index]), index)
        except HollowError as error:
            return Failure(index, error.reason, held=True)
        except SolverError as error:
            return Failure(index, f"the design NLP did not converge: {error.status}")

    def finished(index: int, outcome: object, wall: float) -> None:
        assert isinstance(outcome, (Alternative, Failure))
        outcomes[index], seconds[index] = outcome, wall
        if progress:
            progress("refinement", sum(o is not None for o in outcomes), len(candidates))

    if progress:
        progress("refinement", 0, len(candidates))
    refine_in_lanes(len(candidates), refine, solver, lambda: solver.twin(), finished)   # asked only without a fork
    found = [outcome for outcome in outcomes if isinstance(outcome, Alternative)]
    failed = [outcome for outcome in outcomes if isinstance(outcome, Failure)]
    if not found:       # the failures are the whole answer: each held one says what its curves are unheld
        failed = [replace(f, reason=f"{f.reason}; {solver.without_hold(candidates[f.start])}") if f.held else f
                  for f in failed]
    size = reach(problem)
    merged = merge(_other_strokes(problem, solver, candidates, merge(found, size)), size)
    merged = [_convex_if_possible(problem, solver, candidates, alternative) for alternative in merged]
    return rank(merge(merged, size), size), failed, seconds


def _other_strokes(problem: FiveBarProblem, solver: DesignSolver, candidates: list[Candidate],
                   alternatives: list[Alternative]) -> list[Alternative]:
    """Each alternative, or the best design the solver reaches from it with a return point moved to another
    pass of P by it (``DesignSolver.restroke``) when that ranks above it (a larger smallest transmission angle,
    beyond ``ANGLE_TIE``) and passes its checks. Which pass the NLP holds a return point on is fixed by its
    start, and the max-min can have its better optimum on the other pass (on the bundled example P8 at
    carrier turn 219 deg instead of 304 deg: 6.74 deg instead of 6.36). The re-solves of all the alternatives
    run in the lanes of ``fivebar.lanes`` (two at a time), in order, lane 0 on ``solver``."""
    moves = [(alternative, point, turn) for alternative in alternatives
             for point, turn in other_passes(problem, alternative.design)]
    judged: list[Alternative | Failure | None] = [None] * len(moves)

    def restroke(lane_solver: DesignSolver, index: int) -> Alternative | Failure | None:
        alternative, point, turn = moves[index]
        first = alternative.starts[0]
        try:
            return assess(problem, lane_solver.restroke(candidates[first], alternative.design, point, turn), first)
        except SolverError:
            return None

    def finished(index: int, outcome: object, wall: float) -> None:
        assert outcome is None or isinstance(outcome, (Alternative, Failure))
        judged[index] = outcome

    refine_in_lanes(len(moves), restroke, solver, lambda: solver.twin(), finished)
    best = {id(alternative): alternative for alternative in alternatives}
    for (alternative, point, turn), moved in zip(moves, judged, strict=True):
        if isinstance(moved, Alternative) and \
                moved.transmission_angle > best[id(alternative)].transmission_angle * (1 + ANGLE_TIE):
            best[id(alternative)] = replace(moved, starts=alternative.starts, restroke=(
                f"{problem.return_labels[point]} moved from its pass at carrier turn "
                f"{np.degrees(alternative.design.stroke.carrier_turns[point]):.1f} deg to the one at "
                f"{np.degrees(turn):.1f} deg (smallest transmission angle at E "
                f"{np.degrees(alternative.transmission_angle):.3f} -> {np.degrees(moved.transmission_angle):.3f} deg)"))
    return [best[id(alternative)] for alternative in alternatives]


def _convex_if_possible(problem: FiveBarProblem, solver: DesignSolver, candidates: list[Candidate],
                        alternative: Alternative) -> Alternative:
    """The alternative with convex (rack-cut) pitch curves when the solver reaches them from it and the
    result passes its own evaluation; else the alternative, its design noting why its curves are not."""
    first = alternative.starts[0]
    design = solver.make_convex(candidates[first], alternative.design)
    if design is alternative.design or design.convexity_note:
        return replace(alternative, design=design)
    judged = assess(problem, design, first)
    if isinstance(judged, Failure):
        return replace(alternative, design=replace(alternative.design, convexity_note=(
            f"the convex design IPOPT reached fails its checks ({judged.reason}); "
            f"{concavity_text(alternative.design)}")))
    return replace(judged, starts=alternative.starts, restroke=alternative.restroke)


def with_gear_sizes(problem: FiveBarProblem, alternative: Alternative) -> Alternative:
    """The alternative with the whole-tooth sizes of its train, or the reason it has none."""
    design = alternative.design
    gears: TrainSize | str
    try:
        gears = train_size(design.relative_angle, float(design.mech.carrier_length), problem.gearing, problem.source)
    except TransplanterError as error:
        gears = str(error)
    return replace(alternative, gears=gears)

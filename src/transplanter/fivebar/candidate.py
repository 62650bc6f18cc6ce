"""Candidate five-bars judged over a whole turn: key-pose relative angles, return stroke,
fitted relative angle, and the conditions a gear-driven five-bar must meet.

Conditions (each failure is named in ``defects``):
- the relative angle rho increases through the key poses (order: the gears never reverse);
- the B-E-F assembly is the same at the four key poses (branch);
- the carrier can turn fully (five-bar crank existence, see ``crank_exists``);
- the return points have a consistent inverse kinematics (``return_stroke``);
- the fitted rho(c) is strictly increasing, with the ratio i0 = 1/rho' inside the bounds;
- the chain closes all round with sin^2(angle EBF) above the margin (eq 10).

The fitted rho(c) is the least-bending spline through the key poses and a return stroke; the strokes are
tried cheapest first until one meets the last three conditions. Where none does, ``hold`` tries them again
with the least-bending spline that keeps those conditions at the grid turns (``held_relative_angle``), which
exists whenever any spline through the points does: a problem with a subset of another's return points
then keeps every five-bar the other keeps.

``judge_candidates`` checks a whole batch of mechanisms with array operations over
(mechanisms x carrier turns), each stage only on the mechanisms the earlier ones kept;
``evaluate_candidate`` is the same judgement of one mechanism.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from transplanter.fivebar.held_relative_angle import hold_relative_angle
from transplanter.fivebar.linkage import FiveBar, assembly_branch
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.fivebar.relative_angle import RelativeAngle, fit_relative_angle, negative_intervals, ratio_range
from transplanter.fivebar.return_stroke import SEQUENCE_LIMIT, ReturnStroke, stroke_sequences
from transplanter.geometry.planar import TWO_PI

#: Carrier turns at which the whole-turn conditions are checked.
GRID = np.linspace(0, TWO_PI, 720, endpoint=False)
BRANCH = "branch: the B-E-F assembly differs between key poses"
CRANK = "crank: the carrier cannot turn fully"
RETURN = "return: no assembly reaches the return points in order"


@dataclass(frozen=True)
class Candidate:
    mech: FiveBar
    key_relative_angles: np.ndarray
    defects: list[str] = field(default_factory=list)
    stroke: ReturnStroke | None = None
    relative_angle: RelativeAngle | None = None
    min_margin: float = float("nan")
    ratio_range: tuple[float, float] = (float("nan"), float("nan"))
    unheld_defects: tuple[str, ...] = ()     # what the least-bending relative angle broke, when this one is held
    #: The key poses (mm, rad) and carrier turns (rad) the candidate was found for, when they are a pose set
    #: drawn inside the problem's bands rather than the problem's own (None).
    poses: np.ndarray | None = None
    carrier_turns: np.ndarray | None = None

    def key_poses(self, problem) -> tuple[np.ndarray, np.ndarray]:
        """The key poses and carrier turns the candidate meets: its own pose set, or the problem's."""
        if self.poses is None or self.carrier_turns is None:
            return problem.poses, problem.carrier_turns
        return self.poses, self.carrier_turns

    @property
    def feasible(self) -> bool:
        return not self.defects

    @property
    def passed(self) -> bool:
        """A candidate passes its checks when it is feasible (as a given design is judged)."""
        return self.feasible

    @property
    def failures(self) -> list[str]:
        """The conditions it violates (``defects``)."""
        return list(self.defects)


def crank_exists(mech: FiveBar):
    """The carrier turns fully iff the chain A-F-E-B (L2, L3, L4) spans every |AB| in
    [|L5 - L1|, L5 + L1]: at most L2 + L3 + L4, at least 2 max(L2, L3, L4) - (L2 + L3 + L4).
    A bool, or one per mechanism of a batch."""
    chain = np.stack([mech.rod_length, mech.link_length, mech.receiving_length], -1)
    frame = np.hypot(mech.hinge_b[..., 0], mech.hinge_b[..., 1])
    length, longest = chain.sum(axis=-1), chain.max(axis=-1)
    return (frame + mech.carrier_length <= length) & (abs(frame - mech.carrier_length) >= 2 * longest - length)


def range_values(problem: FiveBarProblem, mech: FiveBar) -> dict:
    """The quantities that ``[ranges]`` limit (mm), for a mechanism or each of a batch."""
    e, f = mech.plate_points(problem.poses[0])
    return {"ep": mech.ep, "fp": mech.fp, "x_e": e[..., 0], "x_f": f[..., 0]}


def ranges_outside(problem: FiveBarProblem, mech: FiveBar, slack: float = 0.0) -> tuple[dict, dict]:
    """The quantities ``[ranges]`` limit (``range_values``) and, per range, which mechanisms of a batch lie
    outside it by more than ``slack`` (mm)."""
    values = range_values(problem, mech)
    return values, {key: ~((low - slack <= values[key]) & (values[key] <= high + slack))[:, 0]
                    for key, (low, high) in problem.ranges.items()}


def whole_turn(mech: FiveBar, relative: RelativeAngle, grid: np.ndarray = GRID) -> tuple:
    """Smallest closure margin over the grid, and rho' on it (one row per mechanism of a batch)."""
    state = mech.forward(grid, relative.evaluate(grid))
    return np.min(state["margin"], axis=-1), relative.evaluate(grid, 1)


def range_defect(key: str, value: float, bounds: tuple[float, float]) -> str:
    return f"ranges.{key} = {value:.2f} outside [{bounds[0]:g}, {bounds[1]:g}]"


def order_defect(rho: np.ndarray) -> str:
    return ("order: the relative angle does not increase through the key poses "
            f"({', '.join(f'{v:.1f}' for v in np.degrees(rho))} deg)")


def monotonic_defect(slope: np.ndarray) -> str:
    spans = ", ".join(f"{a:.1f}-{b:.1f}" for a, b in negative_intervals(GRID, slope))
    return f"monotonic: rho' <= 0 (down to {slope.min():.3f}) for carrier turns {spans} deg"


def ratio_defect(low: float, high: float, bounds: tuple[float, float]) -> str:
    return f"ratio: i0 spans [{low:.3f}, {high:.3f}], outside {list(bounds)}"


def closure_defect(margin: float, minimum: float) -> str:
    return f"closure: min sin^2(EBF) = {margin:.4f} < {minimum:g}"


def _spline_failures(problem: FiveBarProblem, margin, lowest, ratios) -> np.ndarray:
    """(monotonic, ratio, closure) stacked on the first axis: which fitted relative angles break each, from their
    smallest closure margin, smallest rho' and (i0 min, i0 max) (last axis of ``ratios``)."""
    monotonic = ~(lowest > 0)
    ratio = ~monotonic & ((ratios[..., 0] < problem.ratio_bounds[0]) | (ratios[..., 1] > problem.ratio_bounds[1]))
    return np.stack([monotonic, ratio, ~(margin >= problem.min_closure_margin)])


@dataclass(frozen=True)
class _Fit:
    """A relative angle fitted through the key poses and a return stroke, and its whole-turn figures."""

    stroke: ReturnStroke
    relative: RelativeAngle
    margin: float
    ratios: np.ndarray          # (i0 min, i0 max)
    slope: np.ndarray           # rho' on GRID

    def failures(self, problem: FiveBarProblem) -> np.ndarray:
        return _spline_failures(problem, self.margin, self.slope.min(), self.ratios)

    def defects(self, problem: FiveBarProblem) -> list[str]:
        monotonic, ratio, closure = self.failures(problem)
        return ([monotonic_defect(self.slope)] if monotonic else []) + (
            [ratio_defect(self.ratios[0], self.ratios[1], problem.ratio_bounds)] if ratio else []) + (
            [closure_defect(self.margin, problem.min_closure_margin)] if closure else [])


def _least_bending_fits(problem: FiveBarProblem, mech: FiveBar, rho: np.ndarray,
                        judged: np.ndarray) -> tuple[dict[int, _Fit], dict[int, list[ReturnStroke]]]:
    """For each of the ``judged`` mechanisms (rows of the batch) that has consistent return strokes: the
    least-bending relative angle through the first stroke (cheapest first) with which it meets the
    conditions, or else through the cheapest; and its strokes, cheapest first."""
    turns = problem.carrier_turns
    sequences = stroke_sequences(mech[judged], problem.return_points, turns[-1], rho[judged, 0], rho[judged, -1],
                                 problem.poses[-1, 2])
    owner, rank = judged[sequences.owner], sequences.rank()
    strokes = [ReturnStroke(*(values[row] for values in (sequences.stroke.carrier_turns,
                                                          sequences.stroke.relative_angles,
                                                          sequences.stroke.directions))) for row in range(len(owner))]
    fits: dict[int, _Fit] = {}
    met = np.zeros(len(rho), bool)
    for place in range(SEQUENCE_LIMIT):      # each mechanism's next stroke, until one meets the conditions
        rows = np.flatnonzero((rank == place) & ~met[owner])
        if not rows.size:
            break
        relative = fit_relative_angle(
            np.concatenate([np.broadcast_to(turns, (len(rows), len(turns))),
                            sequences.stroke.carrier_turns[rows]], axis=1),
            np.concatenate([rho[owner[rows]], sequences.stroke.relative_angles[rows]], axis=1), problem.spline_count)
        margin, slope = whole_turn(mech[owner[rows]], relative)
        ratios = np.stack(ratio_range(slope), -1)
        meets = ~np.any(_spline_failures(problem, margin, slope.min(axis=-1), ratios), axis=0)
        met[owner[rows]] = meets
        for i in np.flatnonzero(meets | (place == 0)):
            k = owner[rows[i]]
            fits[k] = _Fit(strokes[rows[i]], RelativeAngle(rho[k, 0], relative.coefficients[i]), margin[i], ratios[i],
                           slope[i])
    runs = np.split(np.arange(len(owner)), np.flatnonzero(np.diff(owner)) + 1)     # rows by mechanism
    return fits, {owner[run[0]]: [strokes[row] for row in run] for run in runs if run.size}


def _held_fit(problem: FiveBarProblem, mech: FiveBar, key_rho: np.ndarray, strokes: list[ReturnStroke]) -> _Fit | None:
    """The held relative angle (``held_relative_angle``) through the first of ``strokes`` with which it meets the
    conditions by the whole-turn check, or None."""
    for stroke in strokes:
        relative = hold_relative_angle(problem, mech, key_rho, stroke, len(GRID))
        if relative is not None:
            margin, slope = whole_turn(mech, relative)
            fit = _Fit(stroke, relative, margin, np.array(ratio_range(slope)), slope)
            if not fit.failures(problem).any():
                return fit
    return None


def judge_candidates(problem: FiveBarProblem, mech: FiveBar, check_ranges: bool = True,
                     hold: bool = False, range_slack: float = 0.0) -> list[Candidate]:
    """Every mechanism of a batch (``mech`` fields (K, 1)) judged at once: one ``Candidate`` each, in order.

    Each mechanism's consistent return strokes (``stroke_sequences``) are tried cheapest first with the
    least-bending relative angle through the key poses and the stroke; the first that meets the conditions is
    kept, or, when none does, the cheapest with what it breaks. With ``hold``, a mechanism none of whose
    strokes meets them so tries them again with the held relative angle (``held_relative_angle``). A range
    is met within ``range_slack`` (mm)."""
    turns = problem.carrier_turns
    rho = mech.relative_angle_at(problem.poses, turns)
    rho = rho[..., :1] + np.mod(rho - rho[..., :1], TWO_PI)
    count = len(rho)
    values, outside = ranges_outside(problem, mech, range_slack)
    ranges = problem.ranges if check_ranges else {}
    outside = outside if check_ranges else {}
    disorder = np.any(np.diff(rho, axis=-1) <= 0, axis=-1)
    e, f = mech.plate_points(problem.poses)
    branch_changes = np.any(assembly_branch(mech.hinge_b, e, f) != mech.branch, axis=-1)
    no_crank = ~crank_exists(mech)[:, 0]
    early = disorder | branch_changes | no_crank | np.any([np.zeros(count, bool), *outside.values()], axis=0)
    fits, strokes = _least_bending_fits(problem, mech, rho, np.flatnonzero(~early))

    candidates = []
    for k in range(count):
        one = mech[k, 0]
        defects = [range_defect(key, values[key][k, 0], ranges[key]) for key, bad in outside.items() if bad[k]]
        if disorder[k]:
            defects.append(order_defect(rho[k]))
        if branch_changes[k]:
            defects.append(BRANCH)
        if no_crank[k]:
            defects.append(CRANK)
        if defects:
            candidates.append(Candidate(one, rho[k], defects))
            continue
        if k not in fits:
            candidates.append(Candidate(one, rho[k], [RETURN]))
            continue
        fit, held = fits[k], None
        if hold and fit.failures(problem).any():
            held = _held_fit(problem, one, rho[k], strokes[k])
        unheld = tuple(fit.defects(problem)) if held else ()
        fit = held or fit
        candidates.append(Candidate(one, rho[k], fit.defects(problem), fit.stroke, fit.relative, fit.margin,
                                    (float(fit.ratios[0]), float(fit.ratios[1])), unheld))
    return candidates


def evaluate_candidate(problem: FiveBarProblem, mech: FiveBar, check_ranges: bool = True,
                       hold: bool = False, range_slack: float = 0.0) -> Candidate:
    """``judge_candidates`` for one mechanism."""
    return judge_candidates(problem, mech.as_batch(), check_ranges, hold, range_slack)[0]

"""Results of the onion-transplanter command and their JSON (the content of report.json)."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from transplanter.gears.result import GearResult
from transplanter.parallelogram.evaluation import DesignFile, Evaluation, problem_design
from transplanter.parallelogram.gear_pair import gear_json
from transplanter.parallelogram.objectives import OBJECTIVES
from transplanter.parallelogram.problem import FILE_NAMES, PUBLISHED_FIELDS, TRANSLATION_ONLY, ParallelogramProblem


def variables_json(design: dict) -> dict:
    """The eight variables as in a file (mm, alpha in degrees)."""
    return {FILE_NAMES[k]: (float(np.degrees(v)) if k == "alpha" else float(v)) for k, v in design.items()
            if k in FILE_NAMES}


def trajectory_json(evaluation: Evaluation) -> dict:
    """``trajectory`` summary of report.json."""
    return {"depth_mm": evaluation.depth, "vx_release_mm_s": evaluation.vx_release,
            "vertical_range_mm": evaluation.vertical_range, "spacing_mm": evaluation.spacing,
            "planting_time_s": evaluation.planting_time, "ax_release_mm_s2": evaluation.ax_release}


def conventions_json(problem: ParallelogramProblem) -> dict:
    c = problem.conventions
    return {"crank_sense": "counterclockwise" if c.crank_sense > 0 else "clockwise",
            "alpha_reference_deg": float(np.degrees(c.alpha_reference)), "alpha_instant": c.alpha_instant,
            "forward": "+x" if c.forward > 0 else "-x", "forward_speed_mm_s": problem.forward_speed,
            "driver_speed_rpm": problem.driver_speed * 60 / (2 * np.pi),
            "crank_pivot_mm": [float(v) for v in problem.crank_pivot], "depth_window_mm": problem.depth_window}


def published_json(given: DesignFile, evaluations: list[Evaluation]) -> dict:
    """``published`` of report.json: the paper's figures, its printed gear values, every evaluation."""
    return {"paper": {k: given.published[k] for k in PUBLISHED_FIELDS if k in given.published},
            "printed": dict(given.printed), "evaluations": [e.to_json() for e in evaluations]}


@dataclass(frozen=True)
class DesignReport:
    """A given design evaluated (``--design``): every reading of its gear and conventions, the
    gear pair through the gear library, and the closed curve under the file's conventions."""

    problem: ParallelogramProblem
    given: DesignFile
    evaluations: list[Evaluation]
    closed: Evaluation
    gear: GearResult
    timings_s: dict = field(default_factory=dict)
    failures: tuple[str, ...] = ()

    @property
    def passed(self) -> bool:
        return not self.failures

    def to_json(self) -> dict:
        return {"source": self.problem.source, "design_source": self.given.source, "title": self.given.title,
                "design": variables_json(self.given.design), "conventions": conventions_json(self.problem),
                "translation_only": [FILE_NAMES[k] for k in TRANSLATION_ONLY],
                "published": published_json(self.given, self.evaluations),
                "gear": gear_json(self.gear), "trajectory": trajectory_json(self.closed),
                "timings_s": self.timings_s}


def objective_values(problem: ParallelogramProblem, evaluation: Evaluation) -> np.ndarray:
    """f1, f2, f3 of an evaluation (mm/s, mm, mm)."""
    return np.array([abs(evaluation.vx_release), abs(evaluation.depth - problem.depth_target),
                     abs(evaluation.vertical_range - problem.vertical_range_target)])


@dataclass(frozen=True)
class Polished:
    """The NLP polish of the chosen design: variables (mm, rad; None when IPOPT failed), their
    independent evaluation, whether they dominate the chosen design, IPOPT's status."""

    variables: dict | None
    evaluation: Evaluation | None
    dominates_start: bool
    status: str
    iterations: int
    solve_seconds: float

    def failures(self, problem: ParallelogramProblem) -> tuple[str, ...]:
        """The polished design must exist, meet Vx = 0 and H = target on the fine grid (to 1e-6 of the
        machine speed and of the target) and dominate its start."""
        if self.variables is None:
            return (f"NLP polish failed (IPOPT status {self.status})",)
        e, out = self.evaluation, []
        if abs(e.vx_release) > 1e-6 * problem.forward_speed:
            out.append(f"polished Vx(t_E) = {e.vx_release:.3g} mm/s on the fine grid, not 0")
        if abs(e.depth - problem.depth_target) > 1e-6 * problem.depth_target:
            out.append(f"polished depth {e.depth:.6f} mm on the fine grid, not {problem.depth_target:g}")
        if not self.dominates_start:
            out.append("the polished design does not dominate the NSGA-II design it started from")
        return tuple(out)

    def to_json(self, problem: ParallelogramProblem) -> dict:
        out = {"status": self.status, "iterations": self.iterations, "solve_seconds": self.solve_seconds,
               "dominates_start": self.dominates_start, "variables": None, "objectives": None, "evaluation": None}
        if self.variables is not None:
            out["variables"] = variables_json(self.variables)
            out["objectives"] = dict(zip(OBJECTIVES, (float(v) for v in objective_values(problem, self.evaluation))))
            out["evaluation"] = self.evaluation.to_json()
        return out


@dataclass(frozen=True)
class ParallelogramResult:
    """A designed onion transplanter: the Pareto designs of NSGA-II, the picked one evaluated again
    independently on a finer grid, its gear pair, and the published optimum for comparison.

    Attributes
    ----------
    problem : ParallelogramProblem
    search : SearchResult
        Pareto designs ranked from the knee (rank 1).
    pick : int
        Rank of the chosen design.
    chosen : dict
        Its eight variables (mm, rad).
    evaluation : Evaluation
        Its independent evaluation (8192 samples per turn).
    gear : GearResult
        Its gear pair through the gear library.
    start : Evaluation
        The file's [design] (start values) evaluated the same way.
    published : list of Evaluation
        The file's [design] under every reading of its gear and conventions (``evaluate_published``).
    failures : tuple of str
        Why the result fails its checks (empty when it passes).
    """

    problem: ParallelogramProblem
    search: object
    pick: int
    chosen: dict
    evaluation: Evaluation
    gear: GearResult
    start: Evaluation
    timings_s: dict
    failures: tuple[str, ...] = ()
    polished: Polished | None = None
    published: list[Evaluation] = field(default_factory=list)

    @property
    def final(self) -> dict:
        """The design the gears, drawings and figures are made for: the polished one, else the chosen one."""
        return self.polished.variables if self.polished is not None and self.polished.variables else self.chosen

    @property
    def final_evaluation(self) -> Evaluation:
        return self.polished.evaluation if self.polished is not None and self.polished.variables else self.evaluation

    @property
    def passed(self) -> bool:
        return not self.failures

    def pareto_json(self) -> list[dict]:
        s = self.search
        rows = []
        for k in range(len(s.designs)):
            variables = variables_json({**self.problem.design, **s.variables(k + 1)})
            rows.append({"rank": k + 1, "variables": variables,
                         "objectives": dict(zip(OBJECTIVES, (float(v) for v in s.objectives[k]))),
                         "depth_mm": float(s.depth[k]), "vx_release_mm_s": float(s.vx_release[k]),
                         "vertical_range_mm": float(s.vertical_range[k]), "center_distance": float(s.center_distance[k])})
        return rows

    def to_json(self) -> dict:
        pareto = self.pareto_json()
        e = self.evaluation
        return {"source": self.problem.source, "title": self.problem.title,
                "conventions": conventions_json(self.problem),
                "translation_only": [FILE_NAMES[k] for k in TRANSLATION_ONLY],
                "searched": [FILE_NAMES[k] for k in self.search.names],
                "search": {"population": self.problem.population, "generations": self.problem.generations,
                           "seed": self.problem.seed, "evaluations": self.search.evaluations,
                           "depth_band_mm": list(self.problem.depth_band), "depth_target_mm": self.problem.depth_target,
                           "vertical_range_target_mm": self.problem.vertical_range_target},
                "pareto": pareto, "knee": pareto[0], "pick": self.pick,
                "chosen": {"variables": variables_json(self.chosen),
                           "objectives": dict(zip(OBJECTIVES, (float(v) for v in objective_values(self.problem, e)))),
                           "evaluation": e.to_json()},
                "start": self.start.to_json(),
                "published": published_json(problem_design(self.problem), self.published),
                "gear": gear_json(self.gear), "trajectory": trajectory_json(self.final_evaluation),
                "polished": None if self.polished is None else self.polished.to_json(self.problem),
                "timings_s": self.timings_s}

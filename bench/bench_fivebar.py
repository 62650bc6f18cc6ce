"""Speed of the five-bar main job, against baselines, in one run.

    python bench/bench_fivebar.py [--part N ...]

BLAS runs single-threaded (``OPENBLAS_NUM_THREADS`` / ``OMP_NUM_THREADS`` = 1, set here
before numpy loads, for this process and the fresh one of part 4).

1. Region sweep: five-bar candidates judged per second (pairing, key-pose conditions,
   return-stroke inverse kinematics, spline fit, whole-turn closure check).
2. Design NLP, built once per problem: the package's IPOPT solver construction, against
   the baseline's, which builds casadi Functions for the objective, its gradient, the
   constraints and their Jacobian (no Hessian: SLSQP approximates it).
3. Design NLP per region candidate, same problem (the first exchange round: the fixed grid,
   from the candidate itself) and the same objective: the package (IPOPT, exact Hessian)
   against scipy SLSQP given casadi's exact gradient and constraint Jacobian (each evaluated once per
   point), for two first-round NLPs (``FIRST_ROUNDS``: the curvature rows off, where both sides solve the NLP
   built without them, and the main job's refinements' own first solve); each side's failures are timed and
   counted, and left out of the medians; where a package solve's time goes (evaluations, iteration callback,
   IPOPT's own work). Then the package's whole refinement of each candidate (every exchange round).
4. The whole main job as the CLI runs it (region, every candidate refined in the two lanes of
   ``fivebar.lanes``, the toothed gears cut and mesh-checked, verification, report, figures,
   drawings and the animation), in a fresh process including start-up; the target is
   under 20 s. From its report: the refinements' wall time per candidate.
5. The bands example the same way, and its time against the fixed-pose main job's (target within 2x).
"""
from __future__ import annotations

import argparse
import os
import time
from pathlib import Path

for _variable in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS"):
    os.environ[_variable] = "1"

# Below, each import may load numpy: after the thread counts are set (E402).
import casadi as ca  # noqa: E402
import numpy as np  # noqa: E402
from fresh_process import cli_run  # noqa: E402  (bench/ is the script's own folder)
from scipy.optimize import minimize  # noqa: E402

from transplanter.errors import SolverError  # noqa: E402
from transplanter.fivebar.design_solver import CONCAVITY_LIMIT, DesignSolver, HollowError  # noqa: E402
from transplanter.fivebar.nlp import length_unit  # noqa: E402
from transplanter.fivebar.problem import load_problem  # noqa: E402
from transplanter.fivebar.region import solution_region  # noqa: E402
from transplanter.solve.ipopt import CONSTRAINT_TOLERANCE  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
EXAMPLE = ROOT / "examples" / "vegetable_planting.toml"
BANDS = ROOT / "examples" / "vegetable_planting_bands.toml"
CANDIDATES = 5
#: The loosest SLSQP tolerance that reaches the package's objective (measured: 1e-10 stops with
#: the design 0.12 mm away and the objective 2% higher; 1e-12 within 1e-7 mm of IPOPT's design).
SLSQP_FTOL = 1e-12
#: The first-round NLPs part 3 compares, by label: (curvature floor, closure in t) as ``DesignSolver.solve``
#: takes them; the second is the first solve of every refinement in the main job.
FIRST_ROUNDS = {"curvature rows off": (None, False),
                f"as the main job's refinements start (a kappa >= {-CONCAVITY_LIMIT:g}, t below the closure "
                "margin too)": (-CONCAVITY_LIMIT, True)}


class SlsqpBaseline:
    """The package's NLP handed to scipy SLSQP, with casadi's exact first derivatives. Values (f, g) and
    derivatives (grad f, Jacobian of g) are each one fused casadi Function, evaluated once per point and
    cached by x: SLSQP asks for f and each constraint block separately at the same x, and a baseline that
    evaluated g and its Jacobian once per request would be slowed by work the method does not need. The
    Jacobian is the one the package hands IPOPT (``layout.jacobian``, through the lifted quantities)."""

    def __init__(self, layout):
        x, p = layout.x, layout.p
        self.values = ca.Function("values", [x, p], [layout.f, layout.g])
        gradient = ca.Function("gradient", [x, p], [ca.gradient(layout.f, x)])
        jacobian = layout.jacobian or ca.Function("jacobian", [x, p], [layout.g, ca.jacobian(layout.g, x)])
        at_x, at_p = ca.MX.sym("x", x.shape[0]), ca.MX.sym("p", p.shape[0])
        self.derivatives = ca.Function("derivatives", [at_x, at_p], [gradient(at_x, at_p), jacobian(at_x, at_p)[1]])

    def solve(self, x0, p, bounds):
        lbg, ubg = bounds.lbg, bounds.ubg
        equal = lbg == ubg
        lower = np.isfinite(lbg) & ~equal
        upper = np.isfinite(ubg) & ~equal
        cache: dict[str, tuple[bytes, tuple]] = {}

        def evaluated(function, v):
            key = v.tobytes()
            if function.name() not in cache or cache[function.name()][0] != key:
                cache[function.name()] = key, tuple(np.asarray(out) for out in function(v, p))
            return cache[function.name()][1]

        def g(v):
            return evaluated(self.values, v)[1].ravel()

        def jac(v):
            return evaluated(self.derivatives, v)[1]

        constraints = [
            {"type": "eq", "fun": lambda v: g(v)[equal] - lbg[equal], "jac": lambda v: jac(v)[equal]},
            {"type": "ineq", "fun": lambda v: np.r_[g(v)[lower] - lbg[lower], ubg[upper] - g(v)[upper]],
             "jac": lambda v: np.r_[jac(v)[lower], -jac(v)[upper]]},
        ]
        box = [(lo if np.isfinite(lo) else None, hi if np.isfinite(hi) else None)
               for lo, hi in zip(bounds.lbx, bounds.ubx, strict=True)]
        result = minimize(lambda v: evaluated(self.values, v)[0].item(), x0,
                          jac=lambda v: evaluated(self.derivatives, v)[0].ravel(),
                          method="SLSQP", bounds=box, constraints=constraints,
                          options={"maxiter": 1000, "ftol": SLSQP_FTOL})
        violation = max(np.abs(g(result.x)[equal] - lbg[equal]).max(),
                        np.fmax(lbg[lower] - g(result.x)[lower], 0).max(initial=0),
                        np.fmax(g(result.x)[upper] - ubg[upper], 0).max(initial=0))
        return result, violation


def operations(function: ca.Function) -> int:
    """The operations of ``function``'s SX parts: the package's Hessian is two SX functions (the quantities, then
    the matrix at them) called in turn."""
    called = function.get_function()
    return sum(function.get_function(name).n_nodes() for name in called) if called else function.n_nodes()


def hessian_evaluations(layout, candidate, nlp, problem, repeats: int = 50) -> None:
    """The Hessian of the Lagrangian IPOPT evaluates every iteration: the package's, formed through the grid
    quantities (``solve.lifted_hessian``), against the one CasADi forms of the same NLP directly, at a
    candidate's start with random multipliers."""
    sigma, lam = ca.SX.sym("sigma"), ca.SX.sym("lam", layout.g.shape[0])
    start = time.perf_counter()
    own = ca.Function("own", [layout.x, layout.p, sigma, lam],
                      [ca.triu(ca.hessian(sigma * layout.f + ca.dot(lam, layout.g), layout.x)[0])])
    own_build = time.perf_counter() - start
    poses, turns = candidate.key_poses(problem)
    arguments = (layout.vector(nlp.start(candidate.mech, candidate.relative_angle, candidate.stroke,
                                         problem.return_points, poses, turns)),
                 layout.parameter_vector(nlp.parameters(candidate.mech.branch, [])), 1.0,
                 np.random.default_rng(0).normal(size=layout.g.shape[0]))
    seconds = []
    for function in (layout.hessian, own):
        begin = time.perf_counter()
        for _ in range(repeats):
            function(*arguments)
        seconds.append((time.perf_counter() - begin) / repeats)
    print(f"Hessian of the Lagrangian per evaluation: package (through the grid quantities) {seconds[0] * 1e3:.2f} ms, "
          f"{operations(layout.hessian):,} operations; CasADi's own of the same NLP {seconds[1] * 1e3:.2f} ms, "
          f"{own.n_nodes():,} operations (built in {own_build:.2f} s); own / package {seconds[1] / seconds[0]:.2f}x")


def ipopt_split(stats: dict, seconds: float) -> str:
    """Where a package solve's ``seconds`` went, from its IPOPT Function's statistics: the NLP's
    evaluations, the iteration callback (``solve.stall``) and the rest (IPOPT's own work, mostly its
    linear algebra, and the start and the independent whole-turn check around the solve)."""
    evaluations = sum(value for key, value in stats.items() if key.startswith("t_wall_nlp_"))
    callback = stats["t_wall_callback_fun"]
    return (f"evaluations {evaluations:.3f} s, iteration callback {callback:.3f} s, "
            f"IPOPT's own and the check {seconds - evaluations - callback:.3f} s")


def per_candidate(problem, parts: set[int]) -> None:
    """Parts 1-3: the region sweep, the NLP's build and the NLP per candidate against SLSQP."""
    start = time.perf_counter()
    region = solution_region(problem)
    sweep = time.perf_counter() - start
    if 1 in parts:
        print(f"region sweep: {len(region.candidates)} candidates in {sweep:.3f} s = "
              f"{len(region.candidates) / sweep:,.0f} candidates/s ({len(region.feasible)} feasible)")
    if not parts & {2, 3}:
        return
    start = time.perf_counter()
    solver = DesignSolver(problem)
    build = time.perf_counter() - start
    start = time.perf_counter()
    baseline = SlsqpBaseline(solver.nlp.layout)
    baseline_build = time.perf_counter() - start
    if 2 in parts:
        print(f"design NLP, built once per problem: package IPOPT solver (exact Hessian) {build:.3f} s; "
              f"baseline casadi objective/gradient/constraint/Jacobian Functions {baseline_build:.3f} s")
    if 3 not in parts:
        return
    nlp = solver.nlp
    hessian_evaluations(nlp.layout, region.feasible[0], nlp, problem)
    for label, (floor, closure) in FIRST_ROUNDS.items():
        # SLSQP solves the NLP the package solves in that round (without the curvature rows where they are off)
        round_baseline = baseline if floor is not None else SlsqpBaseline(solver.nlp_for(floor).layout)
        first_rounds(solver, round_baseline, region.feasible[:CANDIDATES], label, floor, closure)
    refines = []
    for candidate in region.feasible[:CANDIDATES]:
        begin = time.perf_counter()
        try:
            refined = f"objective {solver.refine(candidate).objective:.10e}"
        except SolverError as error:        # the start fails: timed all the same, as the main job spends it
            refined = f"failed ({(error.reason if isinstance(error, HollowError) else error.status)[:60]}...)"
        refines.append(time.perf_counter() - begin)
        print(f"  candidate: package refinement (all exchange rounds) {refines[-1]:.3f} s, {refined}")
    print(f"package refinement per candidate, one solver in this process (median of the first {CANDIDATES}, "
          f"failures included): {np.median(refines):.3f} s, builds of the package solver: {solver.builds}, "
          f"refinements taken from an earlier one that reached the same optimum: {solver.repeats}")


def first_rounds(solver: DesignSolver, baseline: SlsqpBaseline, candidates, label: str, floor: float | None,
                 closure: bool) -> None:
    """The first round of each candidate, by the package (IPOPT) and by SLSQP from the same start: the fixed
    grid, the curvature rows holding a kappa >= ``floor`` (None: off), t held below the closure margin's
    sin^2 too when ``closure``. A start either side fails from is timed on both and left out of the medians."""
    nlp, problem, ipopt = solver.nlp_for(floor), solver.problem, solver.solver_for(floor)
    layout, unit = nlp.layout, length_unit(problem)
    ours, theirs, totals, failed = [], [], [0.0, 0.0], [0, 0]
    print(f"first round, {label}:")
    for candidate in candidates:
        begin = time.perf_counter()
        try:
            design = solver.solve(candidate, curvature_floor=floor, closure_in_quality=closure)
            failure, iterations = None, design.iterations
        except SolverError as error:
            failure, iterations = f"package ended with {error.status}", ipopt.watch.count
        package = time.perf_counter() - begin
        split = ipopt_split(ipopt.function.stats(), package)
        values = nlp.start(candidate.mech, candidate.relative_angle, candidate.stroke, problem.return_points,
                           problem.poses, problem.carrier_turns)
        bounds = nlp.bounds(0, floor, values["least_curvature"], closure)
        begin = time.perf_counter()
        result, violation = baseline.solve(layout.vector(values),
                                           layout.parameter_vector(nlp.parameters(candidate.mech.branch, [])), bounds)
        slsqp = time.perf_counter() - begin
        slsqp_failed = not result.success or violation > CONSTRAINT_TOLERANCE
        totals = [totals[0] + package, totals[1] + slsqp]
        failed = [failed[0] + (failure is not None), failed[1] + slsqp_failed]
        print(f"  candidate: package {package:.3f} s, {iterations} iterations, {package / iterations * 1e3:.1f} ms "
              f"each ({split}); SLSQP {slsqp:.3f} s, {result.nit} iterations, {slsqp / result.nit * 1e3:.1f} ms "
              f"each, {result.nfev} evaluations of the values, objective {result.fun:.10e}, constraint violation "
              f"{violation:.1e}, {result.message!r}")
        if failure is None and slsqp_failed:
            failure = "SLSQP found no feasible optimum"
        if failure is not None:
            print(f"    {failure}; left out of the medians")
            continue
        ours.append(package)
        theirs.append(slsqp)
        reached = layout.vector(nlp.start(design.mech, design.relative_angle, design.stroke,
                                          design.reached_return_points, design.poses, design.carrier_turns))
        lengths = slice(0, layout.variables["relative_angle_start"].start)     # lengths and hinges, before rho1
        print(f"    package objective {design.objective:.10e}, SLSQP's dimensions "
              f"{np.abs(result.x - reached)[lengths].max() * unit:.1e} mm from the package's")
    count = len(candidates)
    print(f"design NLP per candidate, first round, {label} (median of the {len(ours)} of the first {count} where "
          "both converge, same problem and start): "
          f"package IPOPT {np.median(ours):.3f} s, SLSQP with casadi's exact gradient and Jacobian "
          f"{np.median(theirs):.3f} s, baseline / package {np.median(theirs) / np.median(ours):.2f}x (below 1: the "
          f"package is slower); all {count}, failures included: package {totals[0]:.3f} s ({failed[0]} failed), "
          f"SLSQP {totals[1]:.3f} s ({failed[1]} failed), baseline / package {totals[1] / totals[0]:.2f}x")


def main_job(parts: set[int]) -> None:
    """Parts 4 and 5: the main job and the bands example in fresh processes (5 runs the main job too)."""
    seconds, report = cli_run("fivebar", str(EXAMPLE))
    timings = report["timings_s"]
    refined = len(timings["nlp_per_candidate"])
    print(f"main job (fresh process; teeth, figures, drawings and animation included): {seconds:.2f} s "
          f"(target < 20 s); its refinements {timings['nlp']:.2f} s of wall time for {refined} candidates in "
          f"two lanes, {timings['nlp'] / refined:.3f} s per candidate (target < 0.3 s); "
          f"teeth {timings['gears_teeth']:.2f} s")
    if 5 not in parts:
        return
    banded, report = cli_run("fivebar", str(BANDS))
    print(f"bands example (fresh process, everything included): {banded:.2f} s, {banded / seconds:.2f}x the "
          f"fixed-pose main job above (target within 2x); {len(report['key_pose_sets'])} pose sets tried, "
          f"smallest transmission angle at E {report['transmission_angle_min_deg']:.2f} deg")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--part", type=int, action="append", choices=range(1, 6),
                        help="run only this part (repeatable; default: all)")
    parts = set(parser.parse_args().part or range(1, 6))
    print("baseline: the design NLP handed to scipy SLSQP with casadi's exact gradient and constraint Jacobian, "
          "values and derivatives each one fused casadi Function evaluated once per point (per candidate); "
          "the main job has a target, not a baseline (bench_main_job.py compares it with a bare start-up)")
    if parts & {1, 2, 3}:
        per_candidate(load_problem(EXAMPLE), parts)
    if parts & {4, 5}:
        main_job(parts)


if __name__ == "__main__":
    main()

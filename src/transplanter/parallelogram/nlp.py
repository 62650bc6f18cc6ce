"""NLP polish of a Pareto design (IPOPT through CasADi, exact derivatives of the generated functions).

Unknowns: the searched variables but l (the kinematics sees b/l only, so l, the gear's size, would
be a direction of zero curvature; it stays at the start's value) and three driver angles, the planting instant
tau_E and the two ends tau_-, tau_+ of the depth run. Conditions, all exact:
- the planting instant is a lowest point: V_y(tau_E) = 0, A_y(tau_E) >= 0;
- true zero-speed planting: V_x(tau_E) = 0 (an equality, not a weight);
- the run's ends lie on the band's edges, on the sides the start design leaves it:
  X(tau_+-) - X(tau_E) = s_+- w, with tau_- <= tau_E <= tau_+, and the run stays in the band,
  |X - X_E| <= w, at 16 points evenly between tau_E and each end;
- the depth at its target: the higher end (at the start) Y - Y_E = H_target, the other <= H_target;
- the gear: closure through the closed-form center distance; convexity of both curves and
  curvature above the undercut limit at every C = cos(m phi) of the search's grid, both halves.
Objective: the remaining one, f3 = |Y - Y_target| with Y = 2 l1 (derived: E runs on a circle of
radius l1 relative to the machine), as (Y - Y_target)^2 / Y_target^2.

Each angle keeps the whole driver turn it starts in (the closed pair repeats every turn) and stays
within a quarter turn of its start. The polished
design is then evaluated again independently (``evaluation.evaluate``, 8192 samples per turn).
"""
from __future__ import annotations

import time
from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter._generated.gears import (
    conjugate_pitch,
    limacon_center_distance,
    limacon_driven_convexity,
    limacon_driver_convexity,
    polar_curvature,
)
from transplanter._generated.parallelogram import limacon_driven_angle, parallelogram_tip
from transplanter.generated import casadi_function
from transplanter.parallelogram.gear_checks import undercut_limit
from transplanter.parallelogram.kinematics import TWO_PI, mechanisms
from transplanter.parallelogram.problem import ParallelogramProblem
from transplanter.parallelogram.trajectory import TrajectoryMeasures
from transplanter.solve import NLPBuilder, Solver

INTERIOR = np.linspace(0, 1, 18)[1:-1]      # fractions of the way from tau_E to each end
COSINES = np.cos(np.linspace(0.0, np.pi, 33))   # where the gear constraints are imposed (the gear library checks after)
MAX_ITERATIONS = 500


@dataclass(frozen=True)
class Polish:
    """The NLP's design (mm, rad), its driver angles (rad) and IPOPT's report."""

    variables: dict
    angles: np.ndarray          # tau_E, tau_-, tau_+
    status: str
    iterations: int
    seconds: float


def _gear_constraints(m11, m12, b, base, a, limit):
    """Convexity (scale-free) and curvature margin (rho / limit - 1) of both curves, both halves, on COSINES;
    the driver's half is r1 = base + b cos(m phi1) (the onion-transplanter paper's l and b)."""
    driver = casadi_function(limacon_driver_convexity)
    driven = casadi_function(limacon_driven_convexity)
    curvature = casadi_function(polar_curvature)
    conjugate = casadi_function(conjugate_pitch)
    rows = []
    for m in (m11, m12):
        for c in COSINES:
            rows += [driver(b / base, m, c), driven(b / base, m, a / base, c)]
            radius, slope, bend = base + b * c, b * m * np.sqrt(max(1 - c * c, 0.0)), -b * m**2 * c
            rows.append(curvature(radius, slope, bend)[0] / limit - 1)
            r2, s2, b2, _ = conjugate(a, radius, slope, bend)
            rows.append(curvature(r2, s2, b2)[0] / limit - 1)
    return ca.vertcat(*rows)


def polish(problem: ParallelogramProblem, start: dict, measures: TrajectoryMeasures) -> Polish:
    """Polish the design ``start`` (eight variables, mm and rad) whose measures (one design) are given.

    Raises
    ------
    SolverError
        When IPOPT does not succeed (the status is named).
    """
    names = tuple(n for n in problem.bounds if n != "l")
    start_angles = np.array([measures.planting_angle[0], *measures.window[:, 0]])
    laps = np.floor(start_angles / TWO_PI)
    nlp = NLPBuilder()
    searched = nlp.variables("design", len(names), [problem.bounds[n][0] for n in names],
                             [problem.bounds[n][1] for n in names])
    # each angle stays within its whole turn and within a quarter turn of its start
    tau = nlp.variables("angles", 3, np.maximum(TWO_PI * laps, start_angles - np.pi / 2),
                        np.minimum(TWO_PI * (laps + 1), start_angles + np.pi / 2))
    v: dict[str, float | ca.SX] = {**{k: float(val) for k, val in start.items()},
                                   **{n: searched[i] for i, n in enumerate(names)}}
    m12 = 1 / (2 - 1 / v["m11"])
    a = casadi_function(limacon_center_distance)(v["l"], v["b"], 1.0)
    pitch = ca.vertcat(v["l"], v["b"], v["m11"], m12)
    c = problem.conventions
    instant = ca.pi / v["m11"] if c.alpha_instant == "slowest" else 0.0
    phase = c.alpha_reference - c.crank_sense * (casadi_function(limacon_driven_angle)(
        instant, pitch, a)[0] + v["alpha"])
    tip = casadi_function(parallelogram_tip)
    links = ca.vertcat(v["l1"], v["l2"], v["l5"], v["l6"])
    motion = ca.vertcat(problem.driver_speed, problem.forward_velocity)

    def state(angle, lap):
        crank = ca.vertcat(phase + c.crank_sense * lap * TWO_PI, c.crank_sense,
                           a + problem.crank_pivot[0], problem.crank_pivot[1])
        return tip(angle - TWO_PI * lap, angle / problem.driver_speed, pitch, a, links, crank, motion)

    _, bottom, velocity, acceleration = state(tau[0], laps[0])
    ends = [state(tau[1], laps[1])[1], state(tau[2], laps[2])[1]]
    # the run between the bottom and each end stays in the band: (X - X_E) / w in [-1, 1] at interior points
    interior = []
    for k in (1, 2):
        for s in INTERIOR:
            angle = tau[0] + s * (tau[k] - tau[0])
            lap = np.floor((start_angles[0] + s * (start_angles[k] - start_angles[0])) / TWO_PI)
            interior.append((state(angle, lap)[1][0] - bottom[0]) / problem.depth_window)
    # the sides of the band the start leaves on, and its higher end
    end_tips = mechanisms(problem, start).state(measures.window.T)[1][:, 0]
    sides = np.sign(end_tips[0] - measures.lowest[0, 0])
    higher = 1 + int(np.argmax(end_tips[1]))
    w, target = problem.depth_window, problem.depth_target
    limit = undercut_limit(problem.module, problem.pressure_angle)
    speed = problem.forward_speed        # scales: mm/s by the machine speed, mm by the depth target
    nlp.constraints("lowest_point", velocity[1] / speed, 0.0, 0.0)
    nlp.constraints("zero_speed", velocity[0] / speed, 0.0, 0.0)
    nlp.constraints("rising_after", acceleration[1] / (speed * problem.driver_speed), 0.0, np.inf)
    nlp.constraints("band_edges", ca.vertcat((ends[0][0] - bottom[0]) / w - sides[0],
                                             (ends[1][0] - bottom[0]) / w - sides[1]), 0.0, 0.0)
    nlp.constraints("depth_at_target", (ends[higher - 1][1] - bottom[1]) / target - 1, 0.0, 0.0)
    nlp.constraints("depth_within_target", (ends[2 - higher][1] - bottom[1]) / target - 1, -np.inf, 0.0)
    nlp.constraints("angle_order", ca.vertcat(tau[0] - tau[1], tau[2] - tau[0]), 0.0, np.inf)
    nlp.constraints("run_in_band", ca.vertcat(*interior), -1.0, 1.0)
    nlp.constraints("gear", _gear_constraints(v["m11"], m12, v["b"], v["l"], a, limit), 0.0, np.inf)
    objective = (2 * v["l1"] - problem.vertical_range_target) ** 2 / problem.vertical_range_target**2
    solver = Solver("parallelogram_polish", nlp.build(objective), max_iterations=MAX_ITERATIONS)
    began = time.perf_counter()
    solution = solver.solve({"design": [start[n] for n in names], "angles": start_angles},
                            failure=f"{problem.source}: the NLP polish did not converge from the knee")
    seconds = time.perf_counter() - began
    return Polish({**start, **dict(zip(names, (float(val) for val in solution["design"]), strict=True))},
                  solution["angles"], solution.status, solution.iterations, seconds)

"""The solve layer: blocks read back by name, bounds set by name, one success rule, active bounds decided
in one place, and the exchange method, each against a problem whose answer is known in closed form."""
import ast
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from transplanter.errors import SolverError
from transplanter.solve import NLPBuilder, Solver, StallRule, exchange, periodic_peaks

SRC = Path(__file__).resolve().parents[2] / "src" / "transplanter"


def test_values_go_in_and_come_back_by_name_and_a_new_block_moves_none_of_the_others():
    nlp = NLPBuilder()
    a = nlp.variables("a", 2)
    m = nlp.variables("m", (3, 2))
    nlp.constraints("row", a[0] + m[2, 1], 0.0, 0.0)
    layout = nlp.build(ca.sumsqr(a))
    matrix = np.arange(6.0).reshape(3, 2)
    vector = layout.vector({"a": [7.0, 8.0], "m": matrix})
    assert vector.tolist() == [7.0, 8.0, 0.0, 2.0, 4.0, 1.0, 3.0, 5.0]        # column-major, as casadi's reshape
    assert np.array_equal(layout.variables["m"].read(vector), matrix)
    # the symbol is the same matrix: m[2, 1] is the entry the vector holds at m's (2, 1)
    value = ca.Function("row", [layout.x], [layout.g])(vector)
    assert float(value) == 7.0 + matrix[2, 1]
    with pytest.raises(ValueError, match="missing"):
        layout.vector({"a": [1.0, 2.0]})
    with pytest.raises(ValueError, match="twice"):
        nlp.variables("a", 1)


def test_bounds_are_set_by_block_name_and_touch_nothing_else():
    nlp = NLPBuilder()
    x = nlp.variables("x", 3, -1.0, 1.0)
    nlp.constraints("first", x, 0.0, 2.0)
    nlp.constraints("second", x[0] - x[1], -3.0, 3.0)
    layout = nlp.build(ca.sumsqr(x))
    bounds = layout.bounds().free_rows("first", slice(1, None)).fix("x", 0.5, [2])
    assert bounds.lbg.tolist() == [0.0, -np.inf, -np.inf, -3.0] and bounds.ubg.tolist() == [2.0, np.inf, np.inf, 3.0]
    assert bounds.lbx.tolist() == [-1.0, -1.0, 0.5] and bounds.ubx.tolist() == [1.0, 1.0, 0.5]
    assert layout.bounds().lbg.tolist() == [0.0, 0.0, 0.0, -3.0]        # a fresh copy each time


def _box_problem():
    """min (x - 2)^2 + (y + 1)^2 + sum (z - 1)^2 with x <= 1, y >= -5, x + y >= 0.5 and z_k >= c_k: the
    optimum is x = 1, y = -0.5 (both named bounds on), y's own bound slack, z_k = max(1, c_k)."""
    nlp = NLPBuilder()
    x = nlp.variables("x", 1, -np.inf, 1.0, names=(None, ("x", "upper")))
    y = nlp.variables("y", 1, -5.0, np.inf, names=(("y", "lower"), None))
    z = nlp.variables("z", 3)
    nlp.constraints("sum", x + y, 0.5, np.inf, names=(("sum", "lower"), None))
    # a bound on 1/ratio-like rows: the row's lower bound is the named quantity's upper bound
    nlp.constraints("z_floor", z, [0.0, 2.0, 3.0], np.inf, names=(("ceiling", "upper"), None))
    layout = nlp.build((x - 2) ** 2 + (y + 1) ** 2 + ca.sumsqr(z - 1))
    return layout


def test_the_bounds_a_solution_sits_on_are_named_with_their_entries_and_the_most_binding_value():
    layout = _box_problem()
    solution = Solver("box", layout).solve({"x": 0.0, "y": 0.0, "z": [0.0, 0.0, 0.0]})
    assert solution["x"][0] == pytest.approx(1.0) and solution["y"][0] == pytest.approx(-0.5)
    assert solution["z"] == pytest.approx([1.0, 2.0, 3.0])
    active = {(b.name, b.side): b for b in solution.active_bounds()}
    assert set(active) == {("x", "upper"), ("sum", "lower"), ("ceiling", "upper")}
    assert active[("x", "upper")].limit == 1.0 and active[("sum", "lower")].block == "sum"
    ceiling = active[("ceiling", "upper")]
    assert ceiling.entries == (1, 2) and ceiling.value == pytest.approx(2.0)    # the least value on a row's floor


def test_what_counts_as_success_is_decided_once_and_a_failure_names_the_status():
    nlp = NLPBuilder()
    x = nlp.variables("x", 1)
    nlp.constraints("impossible", ca.vertcat(x, x), [1.0, -np.inf], [np.inf, 0.0])
    solver = Solver("infeasible", nlp.build(x**2))
    with pytest.raises(SolverError, match=r"no way \(solver status: Infeasible_Problem_Detected\)") as raised:
        solver.solve({"x": 0.3}, failure="no way")
    assert raised.value.status == "Infeasible_Problem_Detected"
    layout = _box_problem()
    with pytest.raises(SolverError) as limited:
        Solver("box", layout, max_iterations=1).solve({"x": 0.0, "y": 0.0, "z": [0.0, 0.0, 0.0]})
    assert limited.value.status == "Maximum_Iterations_Exceeded"


def test_a_stall_stops_the_solve_and_is_named():
    """Every iterate from this start breaks the equality by more than 1e-30 of its scale: with that as the stall
    threshold and a window of 2 the solve stops at its second iterate and says so."""
    nlp = NLPBuilder()
    x = nlp.variables("x", 1)
    nlp.constraints("circle", x**2 - 2.0, 0.0, 0.0)
    solver = Solver("stall", nlp.build(x**2), stall=StallRule(violation=1e-30, iterations=2))
    with pytest.raises(SolverError, match="a stall") as raised:
        solver.solve({"x": 5.0})
    assert solver.watch.count == 2 and solver.watch.stalled and "2 iterations" in raised.value.status


def test_the_exchange_method_finds_the_least_value_of_a_function_over_a_turn():
    """max t subject to t <= f(s) for every s of a turn, f = 1 + 0.3 cos(3 (s - 0.4)) + 0.1 sin(s): solved on
    a grid (a point set's least f), refined by adding the fine grid's worst points, it reaches the fine grid's
    true least f, which a coarse grid alone misses."""
    def f(s):
        return 1 + 0.3 * np.cos(3 * (s - 0.4)) + 0.1 * np.sin(s)

    fine = np.linspace(0, 2 * np.pi, 20000, endpoint=False)

    def solve(points, previous):
        return float(f(points).min())

    def worst(t):
        return fine[periodic_peaks(t - f(fine))]

    coarse = np.linspace(0, 2 * np.pi, 5, endpoint=False)
    t, points = exchange(solve, worst, coarse, rounds=4)
    assert solve(coarse, None) > f(fine).min() + 0.05
    assert t == f(fine).min() and len(points) > len(coarse)


def test_ipopt_is_called_from_one_module_and_generated_functions_are_never_looked_up_by_string():
    calls, by_string = [], []
    for path in SRC.rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "nlpsol":
                calls.append(path.relative_to(SRC).as_posix())
            if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                    and node.func.id in ("casadi_function", "numpy_twin")
                    and any(isinstance(arg, ast.Constant) and isinstance(arg.value, str) for arg in node.args)):
                by_string.append(path.relative_to(SRC).as_posix())
    assert calls == ["solve/ipopt.py"] and by_string == []

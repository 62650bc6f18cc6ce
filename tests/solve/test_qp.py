"""The solve layer's quadratic programs: answers known in closed form, one rule for no solution, one module."""
import ast
from pathlib import Path

import numpy as np
import pytest

from transplanter.errors import SolverError
from transplanter.solve.qp import ROW_STEP, solve_qp

SRC = Path(__file__).resolve().parents[2] / "src" / "transplanter"


def test_the_nearest_point_of_a_plane_and_of_a_box():
    """min |x|^2 / 2 with a . x = 1 is x = a / |a|^2; min |x - c|^2 / 2 within a box is c clipped to it."""
    a = np.array([[1.0, -2.0, 3.0]])
    x = solve_qp(np.eye(3), np.zeros(3), a, np.ones(1), np.ones(1))
    assert np.abs(x - a[0] / (a[0] @ a[0])).max() < 1e-12
    c = np.array([2.0, -3.0, 0.5])
    low, high = np.array([-1.0, -1.0, -1.0]), np.array([1.0, 1.0, 1.0])
    x = solve_qp(np.eye(3), -c, np.eye(3), low, high)
    assert np.abs(x - np.clip(c, low, high)).max() < 1e-12


@pytest.mark.parametrize("rows", [1, ROW_STEP - 1, ROW_STEP, ROW_STEP + 1])
def test_any_number_of_rows_gives_the_same_answer(rows):
    """The same constraint written ``rows`` times (spare rows padded free): the same minimiser."""
    x = solve_qp(np.diag([1.0, 2.0]), np.array([-4.0, 0.0]), np.tile([[1.0, 1.0]], (rows, 1)), np.full(rows, -np.inf),
                 np.full(rows, 1.0))
    # (4, 0) breaks x0 + x1 <= 1; on x0 + x1 = 1, (x0 - 4)^2 / 2 + (1 - x0)^2 is least at x0 = 2
    assert np.abs(x - [2.0, -1.0]).max() < 1e-12


def test_rows_that_cannot_hold_together_raise_one_error_naming_the_status():
    with pytest.raises(SolverError, match=r"the quadratic program has no solution \(solver status: "):
        solve_qp(np.eye(2), np.zeros(2), np.array([[1.0, 0.0], [1.0, 0.0]]), np.array([1.0, -np.inf]),
                 np.array([np.inf, 0.0]))


def test_a_quadratic_program_is_solved_in_one_module():
    calls = [path.relative_to(SRC).as_posix() for path in SRC.rglob("*.py")
             for node in ast.walk(ast.parse(path.read_text()))
             if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
             and node.func.attr in ("conic", "qpsol")]
    assert calls == ["solve/qp.py"]

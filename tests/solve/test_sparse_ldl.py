"""The package's KKT factorisation (solve/sparse_ldl.c) through MA27's entry points, called as IPOPT calls them,
against numpy's dense solve and eigenvalues; and IPOPT with it against IPOPT with MUMPS."""
from __future__ import annotations

import ctypes

import casadi as ca
import numpy as np
import pytest

from transplanter.solve import ipopt, kkt_solver
from transplanter.solve.kkt_solver import kkt_solver_options, library_path

ENTRY = ctypes.POINTER(ctypes.c_int)


def _library() -> ctypes.CDLL:
    path = library_path()
    assert path is not None, "the install did not compile solve/sparse_ldl.c (is there a C compiler?)"
    return ctypes.CDLL(path)


def _int(value: int) -> ctypes.c_int:
    return ctypes.c_int(value)


def _pointer(array: np.ndarray) -> ctypes.c_void_p:
    return array.ctypes.data_as(ctypes.c_void_p)


def factor_and_solve(matrix: np.ndarray, rhs: np.ndarray, workspace: float = 5.0, recycled: np.ndarray | None = None):
    """INFO(1), the negative eigenvalues (INFO(15)), the solution, MA27's IKEEP (its first n: the nodes kept for
    the dense tail after a pivot cancelled) and the last IW, with the upper triangle of ``matrix`` given
    as triplets (diagonal included, zeros kept as entries) and IPOPT's protocol: MA27AD's sizes times
    ``workspace``, grown as MA27BD asks (INFO(1) -3 or -4). IW is allocated zeroed, or first as a copy of
    ``recycled`` where that is as long (a block an earlier solve freed, as IPOPT's uncleared allocation can get)."""
    lib = _library()
    n = matrix.shape[0]
    rows, cols = np.nonzero(np.triu(np.ones_like(matrix)) * (np.triu(matrix) != 0) + np.eye(n))
    values = matrix[rows, cols].copy()
    irn, icn = (rows + 1).astype(np.int32), (cols + 1).astype(np.int32)
    nz = len(values)
    icntl, cntl, info = (ctypes.c_int * 30)(), (ctypes.c_double * 5)(), (ctypes.c_int * 20)()
    lib.ma27id_(icntl, cntl)
    ikeep, iw1 = np.zeros(3 * n, np.int32), np.zeros(2 * n, np.int32)
    liw = _int(2 * (2 * nz + 3 * n + 1))
    iw = np.zeros(liw.value, np.int32)
    nsteps, iflag, ops, maxfrt = _int(0), _int(0), ctypes.c_double(), _int(0)
    lib.ma27ad_(ctypes.byref(_int(n)), ctypes.byref(_int(nz)), _pointer(irn), _pointer(icn), _pointer(iw),
                ctypes.byref(liw), _pointer(ikeep), _pointer(iw1), ctypes.byref(nsteps), ctypes.byref(iflag), icntl,
                cntl, info, ctypes.byref(ops))
    assert info[0] == 0
    la, liw = _int(max(int(workspace * info[4]), nz)), _int(int(workspace * info[5]))    # IPOPT: la >= nz
    for attempt in range(4):
        iw, a = np.zeros(liw.value, np.int32), np.zeros(la.value)
        if attempt == 0 and recycled is not None and len(recycled) == liw.value:
            iw[:] = recycled
        a[:nz] = values
        lib.ma27bd_(ctypes.byref(_int(n)), ctypes.byref(_int(nz)), _pointer(irn), _pointer(icn), _pointer(a),
                    ctypes.byref(la), _pointer(iw), ctypes.byref(liw), _pointer(ikeep), ctypes.byref(nsteps),
                    ctypes.byref(maxfrt), _pointer(iw1), icntl, cntl, info)
        if info[0] == -3:
            liw = _int(2 * info[1])
        elif info[0] == -4:
            la = _int(max(2 * info[1], nz))
        else:
            break
    flag, negative = info[0], info[14]
    x, work = rhs.astype(float).copy(), np.zeros(maxfrt.value)
    if flag in (0, 3):
        lib.ma27cd_(ctypes.byref(_int(n)), _pointer(a), ctypes.byref(la), _pointer(iw), ctypes.byref(liw),
                    _pointer(work), ctypes.byref(maxfrt), _pointer(x), _pointer(iw1), ctypes.byref(nsteps), icntl,
                    info)
    return flag, negative, x, ikeep[:n], iw


def kkt(variables: int, inequalities: int, equalities: int, per_row: int, seed: int, free: int = 0,
        convex: bool = True) -> np.ndarray:
    """IPOPT's augmented system [W + Dx, 0, Jc^T, Jd^T; 0, Ds, 0, -I; Jc, 0, 0, 0; Jd, -I, 0, 0]: each row
    touches ``per_row`` variables; the last ``free`` inequality rows have slacks with no bound (Ds = 0)."""
    rng = np.random.default_rng(seed)
    m = inequalities + equalities

    def jacobian(rows):
        out = np.zeros((rows, variables))
        for r in range(rows):
            out[r, rng.choice(variables, per_row, replace=False)] = rng.normal(size=per_row)
        return out

    hessian = rng.normal(size=(variables, variables))
    hessian = hessian @ hessian.T / variables + 0.1 * np.eye(variables) if convex else hessian + hessian.T
    slack = 10.0 ** rng.uniform(-3, 3, inequalities)
    slack[inequalities - free:] = 0.0
    size = variables + inequalities + m
    matrix = np.zeros((size, size))
    x, s, c = slice(0, variables), slice(variables, variables + inequalities), variables + inequalities
    matrix[x, x] = hessian
    matrix[s, s] = np.diag(slack)
    jc, jd = jacobian(equalities), jacobian(inequalities)
    matrix[c:c + equalities, x] = jc
    matrix[c + equalities:, x] = jd
    matrix[c + equalities:, s] = -np.eye(inequalities)
    return np.triu(matrix.T) + np.triu(matrix.T, 1).T


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("free", [0, 20])
@pytest.mark.parametrize("convex", [True, False])
def test_solution_and_inertia_match_a_dense_solve(seed, free, convex):
    matrix = kkt(variables=30, inequalities=200, equalities=12, per_row=6, seed=seed, free=free, convex=convex)
    rhs = np.random.default_rng(100 + seed).normal(size=matrix.shape[0])
    flag, negative, x, _, _ = factor_and_solve(matrix, rhs)
    eigenvalues = np.linalg.eigvalsh(matrix)
    assert np.abs(eigenvalues).min() > 1e-10 * np.abs(eigenvalues).max()     # the test matrix is regular
    assert flag == 0
    assert negative == int((eigenvalues < 0).sum())
    residual = np.abs(matrix @ x - rhs).max() / (np.abs(matrix).max() * np.abs(x).max())
    assert residual < 1e-12


def test_pivots_lost_to_cancellation_send_their_nodes_to_the_dense_tail():
    """Variables with no curvature (as IPOPT's first matrices have, with zero multipliers) get their pivots from
    rows of both signs, which can cancel: such a node is kept for the tail and the order made again. Over 40 such
    systems the path is taken, and every solution and inertia is still exact."""
    kept_somewhere = 0
    for seed in range(40):
        matrix = kkt(variables=30, inequalities=120, equalities=12, per_row=4, seed=seed, free=10, convex=False)
        flat = np.random.default_rng(seed).choice(30, 12, replace=False)
        matrix[flat, :30] = 0.0
        matrix[:30, flat] = 0.0
        eigenvalues = np.linalg.eigvalsh(matrix)
        if np.abs(eigenvalues).min() <= 1e-10 * np.abs(eigenvalues).max():
            continue                                                       # only regular systems compare
        rhs = np.random.default_rng(200 + seed).normal(size=matrix.shape[0])
        flag, negative, x, kept, _ = factor_and_solve(matrix, rhs)
        kept_somewhere += int(kept.any())
        assert flag == 0
        assert negative == int((eigenvalues < 0).sum())
        assert np.abs(matrix @ x - rhs).max() / (np.abs(matrix).max() * np.abs(x).max()) < 1e-12
    assert kept_somewhere > 0


def test_workspace_grows_as_ipopt_grows_it():
    matrix = kkt(variables=40, inequalities=300, equalities=20, per_row=8, seed=7)
    rhs = np.ones(matrix.shape[0])
    flag, negative, x, _, _ = factor_and_solve(matrix, rhs, workspace=0.05)      # far below what MA27AD advised
    assert flag == 0
    assert np.allclose(matrix @ x, rhs, atol=1e-8)


def test_a_work_block_holding_an_earlier_solves_order_gives_the_answer_a_cleared_one_gives():
    """IPOPT allocates IW without clearing it, so a solve's IW can be the block an earlier solve of the same NLP
    freed, that solve's order whole in it. The order is made from the first matrix's values (its zero diagonals
    paired), so a solve whose rows have lost their bounds (the same entries, 20 slack diagonals now zero) is
    ordered again there: the same solution to the last bit as in a cleared block."""
    earlier_matrix = kkt(variables=30, inequalities=200, equalities=12, per_row=6, seed=11, free=0)
    matrix = kkt(variables=30, inequalities=200, equalities=12, per_row=6, seed=11, free=20)
    assert np.count_nonzero(earlier_matrix != matrix) == 20
    rhs = np.random.default_rng(11).normal(size=matrix.shape[0])
    *_, earlier = factor_and_solve(earlier_matrix, rhs)
    flag, negative, cleared, _, _ = factor_and_solve(matrix, rhs)
    again, negative_again, recycled, _, _ = factor_and_solve(matrix, rhs, recycled=earlier)
    assert flag == again == 0 and negative == negative_again
    assert np.abs(matrix @ cleared - rhs).max() / (np.abs(matrix).max() * np.abs(cleared).max()) < 1e-12
    assert np.array_equal(recycled, cleared)


def test_a_singular_matrix_is_reported_singular():
    matrix = kkt(variables=20, inequalities=60, equalities=5, per_row=4, seed=3)
    matrix[:, 0] = matrix[0, :] = 0.0                                       # a variable in no row, no curvature
    flag, _, _, _, _ = factor_and_solve(matrix, np.ones(matrix.shape[0]))
    assert flag == 3


def test_ipopt_reaches_the_optimum_mumps_reaches():
    """A small NLP with free rows, equality rows and active inequalities: the same optimum either way."""
    assert kkt_solver_options()["ipopt.hsllib"] == library_path()
    x = ca.SX.sym("x", 6)
    g = ca.vertcat(ca.sumsqr(x) - 4, x[0] * x[1] - x[2], ca.sin(x[3]) + x[4], x[5] ** 2 + x[0], x[1] - x[2] ** 3)
    problem = {"x": x, "f": (x[0] - 1) ** 4 + ca.sumsqr(x - ca.DM([2, -1, 0.5, 1, -2, 1])), "g": g}
    bounds = {"lbg": [-np.inf, 0, -np.inf, -1, -np.inf], "ubg": [0, 0, np.inf, np.inf, np.inf], "x0": np.zeros(6)}
    base = {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes", "ipopt.tol": 1e-12}
    optima = []
    for extra in ({}, kkt_solver_options()):
        solver = ca.nlpsol("check", "ipopt", problem, {**base, **extra})
        result = solver(**bounds)
        assert solver.stats()["return_status"] == "Solve_Succeeded"
        optima.append(np.asarray(result["x"]).ravel())
    assert np.abs(optima[0] - optima[1]).max() < 1e-8


def test_without_the_compiled_file_ipopt_keeps_mumps(monkeypatch):
    """An install without a C compiler has no library: the option set then names no linear solver (MUMPS)."""
    monkeypatch.setattr(kkt_solver, "library_path", lambda: None)
    options = ipopt.ipopt_options(ipopt.TOLERANCE, ipopt.MAX_ITERATIONS)
    assert not any(key in options for key in ("ipopt.linear_solver", "ipopt.hsllib", "ipopt.linear_system_scaling"))
    assert "MUMPS" in kkt_solver.kkt_factorisation()       # what the reports then say
    monkeypatch.undo()
    assert ipopt.ipopt_options(ipopt.TOLERANCE, ipopt.MAX_ITERATIONS)["ipopt.hsllib"] == library_path()
    assert kkt_solver.kkt_factorisation().startswith("the package's sparse LDL^T")


def test_the_main_job_report_names_the_factorisation(example_result):
    named = kkt_solver.kkt_factorisation()
    assert example_result.to_json()["nlp"]["kkt_factorisation"] == named
    assert f"KKT systems factored by {named}." in example_result.to_markdown()

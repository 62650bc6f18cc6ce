"""The Hessian of an NLP's Lagrangian through named intermediate quantities.

Where many rows depend on x only through a few quantities each (v = h(x, p): the five-bar's crank angles,
link lengths and the spline's derivatives at each grid point), the Lagrangian is written in z = (x, v) and
its Hessian in x is, by the chain rule,

    d2L/dx2 = [I; dh/dx]^T  d2L/dz2  [I; dh/dx]  +  sum_k dL/dv_k  d2h_k/dx2

(the last term vanishes for the quantities affine in x). d2L/dz2 is sparse in v (a row's block is the
few quantities of its own point), where the Hessian CasADi forms directly in x differentiates every row in
every variable its quantities reach. The result is the same matrix to rounding (tested against CasADi's).
On the five-bar's design NLP: 284,478 operations per evaluation against CasADi's 469,253, 2.0 ms against
3.1 (``bench/bench_fivebar.py`` prints both).

The matrix is left written in z and evaluated as two functions, v = h(x, p) and then the Hessian at (x, v):
writing it in x alone (substituting h into it) cost 0.48 s of the five-bar NLP's 1.39 s build, for the
same operations.
"""
from __future__ import annotations

import casadi as ca


def lifted_hessian(x: ca.SX, p: ca.SX, lifted: ca.SX, values: ca.SX, f: ca.SX, g: ca.SX) -> ca.Function:
    """The upper triangle of the Hessian of ``lam_f f + lam_g . g`` in ``x``, as IPOPT's ``hess_lag``
    (inputs x, p, lam_f, lam_g), where ``f`` and ``g`` are written in ``x`` and the symbols ``lifted``,
    which stand for ``values`` (expressions in ``x`` and ``p``)."""
    lam_f, lam_g = ca.SX.sym("lam_f"), ca.SX.sym("lam_g", g.shape[0])
    z = ca.vertcat(x, lifted)
    lagrangian = lam_f * f + ca.dot(lam_g, g)
    hessian, gradient = ca.hessian(lagrangian, z)
    adjoint = ca.SX.sym("adjoint", lifted.shape[0])         # dL/dv, held fixed in the curvature term
    curvature = ca.hessian(ca.dot(adjoint, values), x)[0]
    chain = ca.vertcat(ca.SX.eye(x.shape[0]), ca.jacobian(values, x))
    full = ca.mtimes([chain.T, hessian, chain]) + ca.substitute(curvature, adjoint, gradient[x.shape[0]:])
    in_z = ca.Function("nlp_hess_l_z", [x, lifted, p, lam_f, lam_g], [ca.triu(full)])
    quantities = ca.Function("lifted_quantities", [x, p], [values])
    inputs = [ca.MX.sym(name, symbol.shape[0]) for name, symbol in
              (("x", x), ("p", p), ("lam_f", lam_f), ("lam_g", lam_g))]
    at_x, at_p, sigma, multipliers = inputs
    return ca.Function("nlp_hess_l", inputs, [in_z(at_x, quantities(at_x, at_p), at_p, sigma, multipliers)],
                       ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])

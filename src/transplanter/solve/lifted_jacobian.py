"""The Jacobian of an NLP's rows through named intermediate quantities, as IPOPT's ``jac_g``.

With the rows g written in x and the lifted quantities v_b = h_b(x, p) (``NLPBuilder.lifted``, one block b
per call), by the chain rule

    dg/dx = dg/dx|_v + sum_b dg/dv_b  dh_b/dx.

Each factor is sparse (a grid point's rows see only its own quantities) and is formed one block at a time:
CasADi's Jacobian of the five-bar's rows in all 1,658 quantities at once took 2.1 s (one row, the train's
correction, sees all 1,152 quadrature slopes, and the coloring over both kinds of column did not separate
them), block by block 0.15 s. Evaluated as two functions and the sparse products (77,696 operations), the
same matrix to rounding takes 0.62-0.72 ms where the Jacobian of the rows with h substituted (140,820
operations) takes 1.03-1.13 ms.
"""
from __future__ import annotations

from collections.abc import Sequence

import casadi as ca


def lifted_jacobian(x: ca.SX, p: ca.SX, lifted: Sequence[tuple[ca.SX, ca.SX]], g: ca.SX) -> ca.Function:
    """``g`` and its Jacobian in ``x`` (IPOPT's ``jac_g``: inputs x, p; outputs g, jac_g_x), where ``g`` is
    written in ``x`` and the symbols of ``lifted`` (symbol, value) pairs, the values expressions in ``x`` and
    ``p``."""
    symbols, values = (list(side) for side in zip(*lifted, strict=True))
    rows = ca.Function("rows_in_z", [x, ca.vertcat(*symbols), p],
                       [g, ca.jacobian(g, x), *(ca.jacobian(g, symbol) for symbol in symbols)])
    quantities = ca.Function("lifted_quantities_and_slopes", [x, p],
                             [ca.vertcat(*values), *(ca.jacobian(value, x) for value in values)])
    at_x, at_p = ca.MX.sym("x", x.shape[0]), ca.MX.sym("p", p.shape[0])
    value, *slopes = quantities(at_x, at_p)
    row, along_x, *along_lifted = rows(at_x, value, at_p)
    jacobian = sum((ca.mtimes(a, b) for a, b in zip(along_lifted, slopes, strict=True)), along_x)
    return ca.Function("nlp_jac_g", [at_x, at_p], [row, jacobian], ["x", "p"], ["g", "jac_g_x"])

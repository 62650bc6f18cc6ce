"""The ratio formula reader: formulas evaluate as numpy does, and constants that give no
finite number are refused with the piece named (never a Python exception)."""
import re

import casadi as ca
import numpy as np
import pytest

from transplanter.gears.ratio_expression import ExpressionError, parse_ratio


@pytest.mark.parametrize("text, reference", [
    ("1 + 0.35*cos(phi) + 0.1*sin(2*phi)", lambda p: 1 + 0.35 * np.cos(p) + 0.1 * np.sin(2 * p)),
    ("(1 + 0.5*cos(phi))**2 / sqrt(2)", lambda p: (1 + 0.5 * np.cos(p)) ** 2 / np.sqrt(2)),
    ("exp(-phi/pi) + log(2 + sin(phi)) - tan(phi/8)",
     lambda p: np.exp(-p / np.pi) + np.log(2 + np.sin(p)) - np.tan(p / 8)),
])
def test_formula_evaluates_as_numpy(text, reference):
    phi = ca.SX.sym("phi")
    value = ca.Function("ratio", [phi], [parse_ratio(text, phi)])
    samples = np.linspace(0, 2 * np.pi, 13)
    assert np.allclose([float(value(p)) for p in samples], reference(samples), rtol=1e-14, atol=0)


@pytest.mark.parametrize("text, piece", [
    ("1/0", "1 / 0"), ("9**9**9**9", "9 ** 9 ** 9"), ("1e308*10", "1e+308 * 10"), ("sqrt(-1)", "sqrt(-1)"),
    ("log(0)", "log(0)"), ("exp(1000)", "exp(1000)"), ("phi/0", "phi / 0"), ("1/(phi - phi)", "1 / (phi - phi)"),
])
def test_constants_without_a_finite_value_are_refused(text, piece):
    with pytest.raises(ExpressionError, match=re.escape(f"'{piece}' is not a finite number")):
        parse_ratio(text, ca.SX.sym("phi"))

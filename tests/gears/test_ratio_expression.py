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


@pytest.mark.parametrize("text, piece, reason", [
    ("(-1)**0.5", "(-1) ** 0.5", "is not a real number (a negative base to a fractional power)"),
    ("1 + (-8)**(1/3)", "(-8) ** (1 / 3)", "is not a real number (a negative base to a fractional power)"),
    ("1" + "0" * 400, "1" + "0" * 39 + "... (401 characters)", "is not a finite number (beyond float range"),
])
def test_complex_values_and_integers_beyond_float_range_are_refused(text, piece, reason):
    with pytest.raises(ExpressionError, match=re.escape(f"'{piece}' {reason}")):
        parse_ratio(text, ca.SX.sym("phi"))


def test_a_negative_base_to_a_whole_power_is_real():
    assert parse_ratio("(-2)**3", ca.SX.sym("phi")) == -8.0


@pytest.mark.parametrize("formula", ["(-1)**0.5", "1 + (-8)**(1/3)", "1" + "0" * 400])
def test_the_gear_command_refuses_them_in_one_line(tmp_path, capsys, formula):
    from pathlib import Path

    from transplanter.cli import main
    example = Path(__file__).resolve().parents[2] / "examples" / "gear_ratio_formula.toml"
    text = example.read_text()
    start = text.index("expression = ")
    line_end = text.index("\n", start)
    problem = tmp_path / "ratio.toml"
    problem.write_text(text[:start] + f'expression = "{formula}"' + text[line_end:])
    assert main(["gear", str(problem)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "driver.expression" in err and "Traceback" not in err, err

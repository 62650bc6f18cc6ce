"""A transmission ratio written as a formula of phi, read safely into a casadi expression.

Allowed: numbers, ``phi``, ``pi``, + - * / **, parentheses and cos, sin, tan, exp, sqrt, log.
Anything else is refused with the offending piece named; nothing is evaluated by Python
but arithmetic on constants, which must stay finite (``1/0``, ``9**9**9**9`` are refused), and
the text is bounded (``MAX_LENGTH`` characters, nesting as deep as Python's parser goes).
"""
from __future__ import annotations

import ast
import math

import casadi as ca

_FUNCTIONS = {"cos": ca.cos, "sin": ca.sin, "tan": ca.tan, "exp": ca.exp, "sqrt": ca.sqrt, "log": ca.log}
_OPERATORS = {ast.Add: lambda a, b: a + b, ast.Sub: lambda a, b: a - b, ast.Mult: lambda a, b: a * b,
              ast.Div: lambda a, b: a / b, ast.Pow: lambda a, b: a**b}


#: Longest formula read: a ratio fits in a line or two, and the parse and build cost grow with the text.
MAX_LENGTH = 1000


class ExpressionError(ValueError):
    """The text is not a formula of the allowed form; the message names the piece."""


def parse_ratio(text: str, phi: ca.SX) -> ca.SX:
    """The casadi expression of ``text``, a formula of ``phi``; ExpressionError names what is wrong."""
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"{len(text)} characters; expected at most {MAX_LENGTH}")
    try:
        return _build(ast.parse(text, mode="eval").body, phi)
    except SyntaxError as error:
        raise ExpressionError(f"not a formula ({error.msg})") from None
    except (RecursionError, MemoryError):
        raise ExpressionError("nested deeper than the parser goes") from None


def _build(node, phi):
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return _finite(node, lambda: float(node.value))
    if isinstance(node, ast.Name) and node.id in ("phi", "pi"):
        return phi if node.id == "phi" else math.pi
    if isinstance(node, ast.BinOp) and type(node.op) in _OPERATORS:
        return _finite(node, lambda: _OPERATORS[type(node.op)](_build(node.left, phi), _build(node.right, phi)))
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        value = _build(node.operand, phi)
        return -value if isinstance(node.op, ast.USub) else value
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in _FUNCTIONS
            and len(node.args) == 1 and not node.keywords):
        return _finite(node, lambda: _FUNCTIONS[node.func.id](_build(node.args[0], phi)))
    raise ExpressionError(f"'{ast.unparse(node)}' is not allowed (numbers, phi, pi, + - * / **, "
                          f"{', '.join(_FUNCTIONS)})")


def _finite(node, evaluate):
    """``evaluate()``, refused when constants alone give no finite real number (casadi folds them into an SX
    constant; Python raises for float division by zero and overflow, and an integer beyond float range, and
    gives a complex number for a negative base to a fractional power)."""
    try:
        value = evaluate()
    except (ZeroDivisionError, OverflowError):
        value = math.nan
    if isinstance(value, complex):
        raise ExpressionError(f"'{_cut(ast.unparse(node))}' is not a real number (a negative base to a fractional "
                              "power)")
    if isinstance(value, ca.SX) and value.is_constant():
        value = float(value)
    if isinstance(value, float) and not math.isfinite(value):
        raise ExpressionError(f"'{_cut(ast.unparse(node))}' is not a finite number (beyond float range, or a "
                              "division by zero)")
    return value


def _cut(text: str, longest: int = 60) -> str:
    """A piece of a formula as a message quotes it: whole, or its start and its length."""
    return text if len(text) <= longest else f"{text[:longest - 20]}... ({len(text)} characters)"

"""sympy -> Python source that builds the same expressions with casadi SX or numpy.

Each generated function takes ``lib`` first: a namespace with ``cos``, ``sin``, ``sqrt``,
``atan2``, ``if_else``, ``fmin``, ``fmax`` (see ``transplanter.generated``). Called with
casadi symbols it builds SX graphs (a casadi Function with named inputs and outputs);
called with numpy arrays it is the vectorised twin. Common subexpressions are pulled out
once with ``sympy.cse`` in canonical order, so the output is byte-identical across runs.
"""
from __future__ import annotations

import sympy as sp
from sympy.printing.str import StrPrinter

from derivations.spec import Derived

_LIB_FUNCTIONS = {"cos": "cos", "sin": "sin", "atan2": "atan2"}


class LibPrinter(StrPrinter):
    """Prints plain Python arithmetic; every function goes through ``lib.``."""

    def _print_Function(self, expr):
        name = expr.func.__name__
        if name not in _LIB_FUNCTIONS:
            raise NotImplementedError(f"no lib mapping for function {name}")
        return f"lib.{_LIB_FUNCTIONS[name]}({', '.join(self._print(a) for a in expr.args)})"

    def _print_Pow(self, expr, rational=False):
        base, exponent = expr.args
        if exponent.is_Rational and exponent.q in (1, 2) and exponent != 0:
            root = f"lib.sqrt({self._print(base)})" if exponent.q == 2 else self.parenthesize(base, 1000)
            power = abs(exponent.p)
            text = root if power == 1 else f"{root}**{power}"
            return text if exponent > 0 else f"1/{text if power == 1 else '(' + text + ')'}"
        raise NotImplementedError(f"no lib mapping for power {expr}")

    def _print_Min(self, expr):
        return self._fold("fmin", expr.args)

    def _print_Max(self, expr):
        return self._fold("fmax", expr.args)

    def _fold(self, name, args):
        text = self._print(args[0])
        for arg in args[1:]:
            text = f"lib.{name}({text}, {self._print(arg)})"
        return text

    def _print_Piecewise(self, expr):
        *pieces, (last, last_condition) = expr.args
        if last_condition != sp.true:
            raise NotImplementedError("Piecewise needs a final True branch")
        text = self._print(last)
        for value, condition in reversed(pieces):
            text = f"lib.if_else({self._print(condition)}, {self._print(value)}, {text})"
        return text

    def _print_Float(self, expr):
        return repr(float(expr))


def print_function(derived: Derived) -> str:
    """Source of one generated function ``name(lib, *input_groups) -> tuple of output lists``."""
    printer = LibPrinter({"full_prec": False})
    outputs = [e for _, group in derived.outputs for e in group]
    replacements, reduced = sp.cse(outputs, symbols=sp.numbered_symbols("_t"), order="canonical")
    args = ", ".join(["lib", *(name for name, _ in derived.inputs)])
    lines = [f"def {derived.name}({args}):", f'    """{derived.doc}"""']
    # Unpack only the inputs the expressions read: an unused local would be dead code.
    used = set().union(*(e.free_symbols for e in (*(expr for _, expr in replacements), *reduced)))
    for name, group in derived.inputs:
        for k, symbol in enumerate(group):
            if symbol in used:
                lines.append(f"    {symbol.name} = {name}[{k}]")
    for symbol, expr in replacements:
        lines.append(f"    {symbol.name} = {printer.doprint(expr)}")
    results, start = [], 0
    for _, group in derived.outputs:
        chunk = reduced[start:start + len(group)]
        start += len(group)
        results.append("[" + ", ".join(printer.doprint(e) for e in chunk) + "]")
    lines.append(f"    return ({', '.join(results)},)")
    return "\n".join(lines) + "\n"


def print_signatures(functions: list[Derived]) -> str:
    """``SIGNATURES``: name -> ((input name, size), ...), ((output name, size), ...)."""
    lines = ["SIGNATURES = {"]
    for d in functions:
        ins = ", ".join(f'("{n}", {len(g)})' for n, g in d.inputs)
        outs = ", ".join(f'("{n}", {len(g)})' for n, g in d.outputs)
        lines.append(f'    "{d.name}": (({ins},), ({outs},)),')
    lines.append("}")
    return "\n".join(lines) + "\n"

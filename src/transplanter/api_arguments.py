"""Checks of what a caller hands to the public API: a problem to a synthesis, a result to the figures and
drawings. A wrong object is refused with a ProblemError that says what was expected and where it comes from."""
from __future__ import annotations

from transplanter.errors import ProblemError
from transplanter.toml_fields import shown


def require_result(result, kind: type, module: str):
    """Refuse (ProblemError) a ``result`` that is not a ``kind``, as figures asked of a problem or of None."""
    if not isinstance(result, kind):
        raise ProblemError(f"result = {shown(type(result).__name__)}: expected a {kind.__name__} (from "
                           f"transplanter.{module}.synthesize(problem))")


def require_problem(problem, kind: type, module: str):
    """Refuse (ProblemError) a ``problem`` that is not a ``kind``, as a synthesis given a path or None."""
    if not isinstance(problem, kind):
        raise ProblemError(f"problem = {shown(problem)!r}: expected a {kind.__name__} (from transplanter.{module}."
                           f"load_problem(path) or parse_problem(dict))")

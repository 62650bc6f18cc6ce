"""Checks of what a caller hands to the public API: a problem to a synthesis, a result to the figures and
drawings, the options of a synthesis. A wrong object is refused with a ProblemError that names the argument, says
what was expected and where it comes from; an object is named by its type, never by a repr of its arrays."""
from __future__ import annotations

import os
from numbers import Integral, Real

from transplanter.errors import ProblemError
from transplanter.toml_fields import shown


def _described(value) -> str:
    """``value`` as a message names it: a plain value (None, text, a number, a path) as it is, anything else by
    its type."""
    if value is None or isinstance(value, (str, os.PathLike, Real)):
        return repr(shown(value))
    return f"a {type(value).__name__}"


def require_result(result, kind: type, module: str):
    """Refuse (ProblemError) a ``result`` that is not a ``kind``, as figures asked of a problem or of None."""
    if not isinstance(result, kind):
        raise ProblemError(f"result = {_described(result)}: expected a {kind.__name__} (from "
                           f"transplanter.{module}.synthesize(problem))")


def require_problem(problem, kind: type, module: str):
    """Refuse (ProblemError) a ``problem`` that is not a ``kind``, as a synthesis given a path, a dict, None or
    another command's problem."""
    if not isinstance(problem, kind):
        raise ProblemError(f"problem = {_described(problem)}: expected a {kind.__name__} (from transplanter.{module}."
                           f"load_problem(path) or parse_problem(dict))")


def require_pick(pick) -> int:
    """``pick`` (the ``--pick`` option) as a whole number of at least 1 (None: 1), before any work starts."""
    if pick is None:
        return 1
    if isinstance(pick, bool) or not isinstance(pick, Integral) or pick < 1:
        raise ProblemError(f"--pick = {_described(pick)}: expected a whole number of at least 1 (1: the first "
                           "ranked)")
    return int(pick)


def require_switch(name: str, value):
    """Refuse (ProblemError) an on/off option ``name`` (``tolerance``, ``polish_nlp``) that is not True or False: a
    text such as "no" would switch it on."""
    if not isinstance(value, bool):
        raise ProblemError(f"{name} = {_described(value)}: expected True or False")


def require_file_switches(animation, solids):
    """Refuse (ProblemError) ``write_files``'s ``animation`` or ``solids`` when it is not True or False."""
    require_switch("animation", animation)
    require_switch("solids", solids)


def require_progress(progress):
    """Refuse (ProblemError) a ``progress`` that is neither None nor a callable ``progress(step, done, total)``."""
    if progress is not None and not callable(progress):
        raise ProblemError(f"progress = {_described(progress)}: expected None or a callable progress(step, done, "
                           "total)")

"""Fields of a nested TOML document addressed by their path: table keys and array indices joined by dots
(``key_poses.2.angle_deg`` is the ``angle_deg`` of the third ``[[key_poses]]`` table)."""
from __future__ import annotations

import copy
from typing import Any

from transplanter.errors import ProblemError

#: What ``read`` gives for a path that the document does not have.
MISSING = object()


def _step(node: Any, part: str) -> Any:
    """The child ``part`` of ``node`` (a key of a table, an index of an array), or MISSING."""
    if isinstance(node, dict):
        return node.get(part, MISSING)
    if isinstance(node, (list, tuple)) and part.isdigit() and int(part) < len(node):
        return node[int(part)]
    return MISSING


def read(document: Any, path: str) -> Any:
    """The value at ``path`` in ``document``, or MISSING."""
    node = document
    for part in path.split("."):
        node = _step(node, part)
        if node is MISSING:
            return MISSING
    return node


def check_path(document: dict, path: Any, source: str, field: str):
    """Refuse (ProblemError) a ``path`` that names no number, text or flag of ``document``; ``field`` is where
    the study file gives the path."""
    value = read(document, path) if isinstance(path, str) and path else MISSING
    if value is MISSING or isinstance(value, (dict, list, tuple)):
        raise ProblemError(f"{source}: {field} = {path!r}: expected the TOML path of a number, text or flag of the "
                           f"problem file (table keys and array indices joined by dots, e.g. key_poses.2.angle_deg)"
                           + ("" if value is MISSING else "; this one names a table or an array"))


def replaced(document: dict, values: dict[str, Any]) -> dict:
    """A copy of ``document`` with the value at each path of ``values`` replaced (every path exists)."""
    copied = copy.deepcopy(document)
    for path, value in values.items():
        *parents, last = path.split(".")
        node: Any = copied
        for part in parents:
            node = node[int(part)] if isinstance(node, list) else node[part]
        if isinstance(node, list):
            node[int(last)] = value
        else:
            node[last] = value
    return copied

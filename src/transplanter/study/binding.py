"""Which requirement a case that failed ran into, named from its one-line error for the feasibility maps."""
from __future__ import annotations

import re

#: A field of a problem file as messages name it: a table and a key (``ranges.ep``, ``conditions.ratio``).
_FIELD = re.compile(r"\b([a-z_]+)\.([a-z_][a-z0-9_]*)\b")
#: The longest label a map's legend shows.
LONGEST_LABEL = 60


def binding_requirement(message: str, problem: dict) -> str:
    """The requirement in ``message`` (a case's one-line error, without its source): the first field of
    ``problem`` it names (e.g. ``ranges.ep``), or else its leading phrase with the numbers masked, so that cases
    stopped by the same requirement share a label."""
    for table, key in _FIELD.findall(message):
        if isinstance(problem.get(table), (dict, list)):
            return f"{table}.{key}"
    phrase = re.split(r"[;(]| \[", message.removeprefix("failed: "))[0]
    phrase = re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "#", phrase).strip(" :,")
    return phrase if len(phrase) <= LONGEST_LABEL else phrase[:LONGEST_LABEL - 3] + "..."

"""Which requirement a case that failed ran into, named from its one-line error for the feasibility maps."""
from __future__ import annotations

import re

#: A field of a problem file as messages name it: a table and a key (``ranges.ep``, ``conditions.ratio``).
_FIELD = re.compile(r"\b([a-z_]+)\.([a-z_][a-z0-9_]*)\b")
#: The longest label a map's legend shows.
LONGEST_LABEL = 48


def binding_requirement(message: str, problem: dict) -> str:
    """The first field of ``problem`` that ``message`` names (e.g. ``ranges.ep``), or else the message's
    leading phrase with its numbers masked, so that cases stopped by the same requirement share a label."""
    for table, key in _FIELD.findall(message):
        if isinstance(problem.get(table), (dict, list)):
            return f"{table}.{key}"
    phrase = re.split(r"[;(]| \[", message.split(": ", 1)[-1] if ": " in message else message)[0]
    phrase = re.sub(r"-?\d+(\.\d+)?(e[-+]?\d+)?", "#", phrase).strip(" :,")
    return phrase if len(phrase) <= LONGEST_LABEL else phrase[:LONGEST_LABEL - 3] + "..."

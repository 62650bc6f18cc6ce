"""How deeply a TOML text nests its arrays and inline tables, found before it is parsed: Python's TOML reader
descends once per level and ends in a RecursionError (a traceback) a few thousand levels down."""
from __future__ import annotations

import re

#: Strings (multi-line first), comments and the brackets that open and close arrays, tables and inline tables.
_TOKENS = re.compile(r'"""(?:[^\\]|\\.)*?"""|\'\'\'.*?\'\'\'|"(?:[^"\\\n]|\\.)*"|\'[^\'\n]*\'|#[^\n]*|[\[\]{}]',
                     re.DOTALL)


def nesting_depth(text: str) -> int:
    """The deepest nesting of brackets ([ ] and { }) outside strings and comments: 1 for ``a = [1]`` or a
    ``[table]`` header, 2 for ``a = [[1]]``. Text that is not valid TOML gives some count; the parser then says
    what is wrong with it."""
    depth = deepest = 0
    for token in _TOKENS.finditer(text):
        mark = token.group()
        if mark in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif mark in "]}":
            depth = max(depth - 1, 0)
    return deepest

"""Which linear solver IPOPT factors its KKT systems with.

The design NLPs have a few dozen variables and a thousand or more constraint rows, each row touching a few
variables. IPOPT's bundled MUMPS takes 8-20 ms a factorisation on the five-bar's design NLP (2,120 rows and
columns), growing with the rows as one dense front of all of them would, where the package's own
sparse LDL^T (``sparse_ldl.c``, compiled at install) takes 0.2-0.4 ms after an ordering of 2-3 ms once a solve.
IPOPT loads it at run time through the entry points of HSL's MA27 (``linear_solver`` ma27, ``hsllib`` the
compiled file); its own scaling (MC19) is HSL's too, so none is asked for. Without the compiled file (an
install without a C compiler) IPOPT keeps MUMPS: the bundled five-bar example gets the same design, more slowly
(a single solve may end at another local optimum: 1 of the main job's 37 in ``bench/bench_kkt_solver.py``).
"""
from __future__ import annotations

from functools import cache
from importlib.util import find_spec

#: The compiled factorisation, an extension module of this package that IPOPT opens as a shared library.
LIBRARY = "transplanter.solve._sparse_ldl"


@cache
def library_path() -> str | None:
    """The compiled factorisation's file, or None where the install could not compile it."""
    spec = find_spec(LIBRARY)
    return spec.origin if spec is not None else None


def kkt_solver_options() -> dict[str, str]:
    """IPOPT's options for the package's factorisation, or none (MUMPS) where it is not compiled."""
    path = library_path()
    if path is None:
        return {}
    return {"ipopt.linear_solver": "ma27", "ipopt.hsllib": path, "ipopt.linear_system_scaling": "none"}


def kkt_factorisation() -> str:
    """Which factorisation IPOPT uses in this install, in words: reports name it, since a run without the compiled
    one is slower."""
    if library_path() is None:
        return "IPOPT's bundled MUMPS (the package's own factorisation was not compiled at install)"
    return "the package's sparse LDL^T (compiled at install)"

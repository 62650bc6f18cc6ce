"""The generated derivations as casadi Functions and as numpy-vectorised twins.

Every generated body takes a backend ``lib`` first; callers import a body by name from
``transplanter._generated.<module>`` (a wrong name fails at import) and hand it here. This module
supplies the two backends and caches one casadi Function per body, with the input and output names
recorded in its generated module's ``SIGNATURES``.
"""
from __future__ import annotations

import functools
import sys
from collections.abc import Callable
from types import SimpleNamespace

import casadi as ca
import numpy as np

CASADI = SimpleNamespace(cos=ca.cos, sin=ca.sin, sqrt=ca.sqrt, atan2=ca.atan2,
                         if_else=ca.if_else, fmin=ca.fmin, fmax=ca.fmax)
NUMPY = SimpleNamespace(cos=np.cos, sin=np.sin, sqrt=np.sqrt, atan2=np.arctan2,
                        if_else=np.where, fmin=np.fmin, fmax=np.fmax)

#: A generated body: ``body(lib, *input_groups)`` -> one tuple of expressions per output group.
Body = Callable[..., tuple]


def signature(body: Body) -> tuple[tuple, tuple]:
    """((input name, size), ...), ((output name, size), ...) of a generated body."""
    return sys.modules[body.__module__].SIGNATURES[body.__name__]


@functools.cache
def casadi_function(body: Body) -> ca.Function:
    """The body as a casadi Function with named inputs and outputs."""
    inputs, outputs = signature(body)
    symbols = [ca.SX.sym(arg, size) for arg, size in inputs]
    results = body(CASADI, *symbols)
    return ca.Function(body.__name__, symbols, [ca.vertcat(*group) for group in results],
                       [arg for arg, _ in inputs], [out for out, _ in outputs])


def numpy_twin(body: Body) -> Callable[..., tuple[np.ndarray, ...]]:
    """Vectorised numpy evaluation: each input group is indexed on its first axis; the
    other axes broadcast. Returns one array per output group, shape (size, *broadcast)."""

    def evaluate(*groups):
        results = body(NUMPY, *(np.asarray(g, dtype=float) for g in groups))
        return tuple(np.array(np.broadcast_arrays(*group)) for group in results)

    evaluate.__name__ = body.__name__
    return evaluate

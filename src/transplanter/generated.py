"""The generated derivations as casadi Functions and as numpy-vectorised twins.

Every generated body takes a backend ``lib`` first; this module supplies the two
backends and caches one casadi Function per body, with the input and output names
recorded in the generated ``SIGNATURES``.
"""
from __future__ import annotations

import functools
import importlib
from types import SimpleNamespace

import casadi as ca
import numpy as np

CASADI = SimpleNamespace(cos=ca.cos, sin=ca.sin, sqrt=ca.sqrt, atan2=ca.atan2,
                         if_else=ca.if_else, fmin=ca.fmin, fmax=ca.fmax)
NUMPY = SimpleNamespace(cos=np.cos, sin=np.sin, sqrt=np.sqrt, atan2=np.arctan2,
                        if_else=np.where, fmin=np.fmin, fmax=np.fmax)


def _body(module: str, name: str):
    generated = importlib.import_module(f"transplanter._generated.{module}")
    return getattr(generated, name), generated.SIGNATURES[name]


@functools.cache
def casadi_function(module: str, name: str) -> ca.Function:
    """casadi Function ``name`` of ``_generated/<module>.py`` with named inputs and outputs."""
    body, (inputs, outputs) = _body(module, name)
    symbols = [ca.SX.sym(arg, size) for arg, size in inputs]
    results = body(CASADI, *symbols)
    return ca.Function(name, symbols, [ca.vertcat(*group) for group in results],
                       [arg for arg, _ in inputs], [out for out, _ in outputs])


def numpy_twin(module: str, name: str):
    """Vectorised numpy evaluation: each input group is indexed on its first axis; the
    other axes broadcast. Returns one array per output group, shape (size, *broadcast)."""
    body, _ = _body(module, name)

    def evaluate(*groups):
        results = body(NUMPY, *(np.asarray(g, dtype=float) for g in groups))
        return tuple(np.array(np.broadcast_arrays(*group)) for group in results)

    evaluate.__name__ = name
    return evaluate

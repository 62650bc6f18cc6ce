"""A package's public API, imported on first use (PEP 562): naming the API in ``__init__``
does not import the whole package (casadi solvers, matplotlib, ezdxf) for a caller that
needs one module of it."""
from __future__ import annotations

import importlib


def lazy_exports(package: str, exports: dict[str, str]):
    """``__getattr__`` and ``__dir__`` for ``package`` that import ``name`` from the module
    ``exports[name]`` of the package the first time ``name`` is asked for."""

    def __getattr__(name: str):
        if name not in exports:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(f"{package}.{exports[name]}"), name)

    def __dir__():
        return sorted(exports)

    return __getattr__, __dir__

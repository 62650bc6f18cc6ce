import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(20261122)


@pytest.fixture(scope="session")
def derived():
    """The derivations as sympy expressions, derived once per session (about 10 s)."""
    import importlib

    from derivations.build import MODULES

    return {(module, d.name): d for module in MODULES for d in importlib.import_module(f"derivations.{module}").derive()}

import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(20261122)


@pytest.fixture(scope="session")
def derived():
    """The derivations as sympy expressions, derived once per session (about 10 s)."""
    from derivations import burmester

    return {d.name: d for d in burmester.derive()}

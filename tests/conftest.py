import numpy as np
import pytest


@pytest.fixture
def rng():
    return np.random.default_rng(20261122)


@pytest.fixture(scope="session")
def derived():
    """The derivations as sympy expressions, derived once per session (about 10 s)."""
    from derivations import burmester, fivebar, gears, planetary

    return {(module.__name__.split(".")[-1], d.name): d for module in (burmester, fivebar, gears, planetary)
            for d in module.derive()}

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


@pytest.fixture(scope="session")
def example_result():
    """The main job on examples/vegetable_planting.toml, synthesised once per test process (the region, every
    candidate refined, the toothed train and the verification take tens of seconds) for the files that read it."""
    from pathlib import Path

    from transplanter import fivebar

    path = Path(__file__).resolve().parents[1] / "examples/vegetable_planting.toml"
    return fivebar.synthesize(fivebar.load_problem(path))

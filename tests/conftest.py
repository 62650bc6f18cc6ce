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


@pytest.fixture(scope="session")
def example_result():
    """The main job on examples/vegetable_planting.toml, synthesised once per test process (the region, every
    candidate refined, the toothed train and the verification take tens of seconds) for the files that read it."""
    from pathlib import Path

    from transplanter import fivebar

    path = Path(__file__).resolve().parents[1] / "examples/vegetable_planting.toml"
    return fivebar.synthesize(fivebar.load_problem(path))

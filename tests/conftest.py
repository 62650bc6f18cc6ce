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

    return {(module, d.name): d
            for module in MODULES for d in importlib.import_module(f"derivations.{module}").derive()}


@pytest.fixture(scope="session")
def example_result():
    """The main job on examples/vegetable_planting.toml, synthesised once per test process (the region, every
    candidate refined, the toothed train and the verification take tens of seconds) for the files that read it."""
    from pathlib import Path

    from transplanter import fivebar

    path = Path(__file__).resolve().parents[1] / "examples/vegetable_planting.toml"
    return fivebar.synthesize(fivebar.load_problem(path))



def pytest_xdist_make_scheduler(config, log):
    """``--dist loadfile``, with every file that reads ``example_result`` in one unit: one worker
    synthesises the example for all of them (about 17 s of CPU), and the other takes the rest file by file."""
    if config.getvalue("dist") != "loadfile":
        return None
    from pathlib import Path

    from xdist.scheduler import LoadFileScheduling

    readers = {path.relative_to(config.rootpath).as_posix() for path in Path(__file__).parent.rglob("test_*.py")
               if "example_result" in path.read_text()}

    class ExampleReadersTogether(LoadFileScheduling):
        def _split_scope(self, nodeid: str) -> str:
            file = super()._split_scope(nodeid)
            return "example_result readers" if file in readers else file

    return ExampleReadersTogether(config, log)

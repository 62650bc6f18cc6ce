import dataclasses
import shutil
from pathlib import Path

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


EXAMPLE = Path(__file__).resolve().parents[1] / "examples/vegetable_planting.toml"


@pytest.fixture(scope="session")
def example_problem():
    """The main job's example, examples/vegetable_planting.toml, read once per test process."""
    from transplanter import fivebar

    return fivebar.load_problem(EXAMPLE)


@pytest.fixture(scope="session")
def example_result(example_problem):
    """The main job on the example, synthesised once per test process (the region, every candidate refined,
    the toothed train and the verification take tens of seconds) for the files that read it."""
    from transplanter import fivebar

    return fivebar.synthesize(example_problem)


RICE = Path(__file__).resolve().parents[1] / "examples/rice_hoe_reverse.toml"
PICKUP = Path(__file__).resolve().parents[1] / "examples/pickup_arm_reverse.toml"


def _reverse_example(path: Path, tolerance: bool):
    """``reverse.synthesize`` itself (not the package's name for it, which ``serve_reverse_examples`` replaces) of
    the example file ``path``."""
    from transplanter.reverse import load_problem
    from transplanter.reverse.synthesis import synthesize

    return synthesize(load_problem(path), tolerance=tolerance)


@pytest.fixture(scope="session")
def rice_result():
    """The rice hoe's reverse train, examples/rice_hoe_reverse.toml, synthesised without the tolerance analysis once
    per test process for the files that only read it (each synthesis takes seconds)."""
    return _reverse_example(RICE, tolerance=False)


@pytest.fixture(scope="session")
def rice_full_result():
    """The rice hoe's reverse train as ``reverse.synthesize`` gives it by default (with the tolerance analysis),
    synthesised once per test process for the files that read it or run a call of it."""
    return _reverse_example(RICE, tolerance=True)


@pytest.fixture(scope="session")
def pickup_result():
    """The pick-up arm's reverse train on its bent carrier, examples/pickup_arm_reverse.toml, synthesised without the
    tolerance analysis once per test process for the files that only read it."""
    return _reverse_example(PICKUP, tolerance=False)


@pytest.fixture(scope="session")
def pickup_full_result():
    """The pick-up arm's reverse train with the tolerance analysis (``reverse.synthesize``'s default), synthesised
    once per test process for the files that read it or run a call of it."""
    return _reverse_example(PICKUP, tolerance=True)


def rice_idler_text() -> str:
    """The rice hoe's file turned into the rice-transplanter paper's train: one idler between identical sun and
    planet (``train.topology = "sun-idler-planet"``, ``train.split = "identical_sun_planet"``)."""
    return RICE.read_text().replace('topology = "sun-intermediate-planet"', 'topology = "sun-idler-planet"').replace(
        'split = "sqrt"', 'split = "identical_sun_planet"')


@pytest.fixture(scope="session")
def rice_idler_command(tmp_path_factory):
    """``transplanter reverse FILE --json --no-tolerance`` on ``rice_idler_text`` (written to problem.toml), run in
    this process once per test process for the command's test of it and the paper's (its train misses the path:
    one synthesis of seconds, which both read): the exit code, stdout, stderr and the result the command
    synthesised."""
    import contextlib
    import io
    import types

    from transplanter import reverse
    from transplanter.cli import main
    from transplanter.reverse.synthesis import synthesize

    path = tmp_path_factory.mktemp("rice_idler") / "problem.toml"
    path.write_text(rice_idler_text())
    results = []

    def kept(problem, tolerance=True):
        results.append(synthesize(problem, tolerance=tolerance))
        return results[-1]
    out, err = io.StringIO(), io.StringIO()
    with pytest.MonkeyPatch.context() as patch, contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        patch.setattr(reverse, "synthesize", kept)
        code = main(["reverse", str(path), "--json", "--no-tolerance"])
    (result,) = results
    return types.SimpleNamespace(code=code, out=out.getvalue(), err=err.getvalue(), result=result)


#: The session's result of each reverse example file, without and with the tolerance analysis.
REVERSE_EXAMPLES = {RICE: ("rice_result", "rice_full_result"), PICKUP: ("pickup_result", "pickup_full_result")}


def serve_reverse_examples(monkeypatch, request):
    """``reverse.synthesize`` of an example file's problem as the file gives it (``REVERSE_EXAMPLES``; any source
    name that resolves to the file) returns the session's result of it without or with the tolerance analysis
    (deterministic, and tested on their own) instead of synthesising the same train again. Any other problem, a
    changed field of the file's included, runs as it is."""
    import pickle

    from transplanter import reverse

    synthesize = reverse.synthesize
    as_read = {path: pickle.dumps(reverse.load_problem(path)) for path in REVERSE_EXAMPLES}

    def once(problem, tolerance=True):
        source = getattr(problem, "source", None)
        path = Path(source).resolve() if isinstance(source, str) else None
        if (path in as_read and type(tolerance) is bool      # a switch given as 0 or "no" is refused as it is
                and pickle.dumps(dataclasses.replace(problem, source=str(path))) == as_read[path]):
            return request.getfixturevalue(REVERSE_EXAMPLES[path][tolerance])
        return synthesize(problem, tolerance=tolerance)
    monkeypatch.setattr(reverse, "synthesize", once)


@pytest.fixture
def rice_result_from_synthesize(monkeypatch, request):
    """``serve_reverse_examples`` for one test: ``reverse.synthesize`` of the rice hoe's file (or the pick-up arm's)
    returns the session's ``rice_result`` or ``rice_full_result`` (``pickup_result``, ``pickup_full_result``)."""
    serve_reverse_examples(monkeypatch, request)


@pytest.fixture
def example_result_from_synthesize(monkeypatch, example_result):
    """``fivebar.synthesize`` of the example file with no pick and the tolerance analysis (as the ``fivebar`` command
    and the README call it)
    returns ``example_result`` (deterministic, and tested on its own) instead of running the same tens of seconds
    again; its progress calls are not made. Any other call runs as it is."""
    from transplanter import fivebar

    synthesize = fivebar.synthesize

    def once(problem, pick=None, progress=None, tolerance=True):
        same = pick is None and tolerance and Path(problem.source).resolve() == EXAMPLE
        return example_result if same else synthesize(problem, pick=pick, progress=progress, tolerance=tolerance)
    monkeypatch.setattr(fivebar, "synthesize", once)



@pytest.fixture(scope="session")
def example_result_drawings(example_result, tmp_path_factory):
    """The files ``fivebar.drawings.write_drawings`` writes of ``example_result`` (sheets, drawings.pdf, tables;
    about 4 s of CPU), written once per test process into one folder that the tests only read."""
    from transplanter.fivebar.drawings import write_drawings

    return write_drawings(example_result, tmp_path_factory.mktemp("example_drawings"))


@pytest.fixture
def example_result_drawings_copied(monkeypatch, example_result, example_result_drawings):
    """The five-bar's file writer (``fivebar.output_files``) given ``example_result`` copies
    ``example_result_drawings`` (the same files, in the order written) instead of drawing them again; any other
    result is drawn as it is."""
    from transplanter.fivebar import output_files

    write_drawings = output_files.write_drawings

    def copied(result, folder):
        if result is not example_result:
            return write_drawings(result, folder)
        Path(folder).mkdir(parents=True, exist_ok=True)
        return [Path(shutil.copy2(path, Path(folder) / path.name)) for path in example_result_drawings]
    monkeypatch.setattr(output_files, "write_drawings", copied)

#: The session's shared results (and the fixtures named after them): a file that names one is a reader.
SHARED_RESULTS = ("example_result", "rice_result", "rice_full_result", "pickup_result", "pickup_full_result",
                  "rice_idler_command")


def pytest_xdist_make_scheduler(config, log):
    """``--dist loadfile``, with every file that reads a shared result (``SHARED_RESULTS``) in one unit: one
    worker synthesises the five-bar example (about 14 s of CPU) and the reverse examples (the rice hoe's with and
    without the tolerance analysis, the pick-up arm's: 3-7 s each) once for all of them, where two workers each
    built those the reverse files read, and the other worker takes the rest file by file (the unit is about a
    third of the suite's CPU, so the two still finish together)."""
    if config.getvalue("dist") != "loadfile":
        return None
    from xdist.scheduler import LoadFileScheduling

    readers = {path.relative_to(config.rootpath).as_posix() for path in Path(__file__).parent.rglob("test_*.py")
               if any(name in path.read_text() for name in SHARED_RESULTS)}

    class ExampleReadersTogether(LoadFileScheduling):
        def _split_scope(self, nodeid: str) -> str:
            file = super()._split_scope(nodeid)
            return "shared result readers" if file in readers else file

    return ExampleReadersTogether(config, log)

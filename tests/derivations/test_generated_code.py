"""The derivation pipeline: every generated function against sympy.lambdify of its derivation at seeded real
points, the stamp, exact regeneration, the drift check, and no sympy at run time."""
import hashlib
import importlib
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from derivations import build
from derivations.build import GENERATED, MODULES, read_stamp
from transplanter.generated import casadi_function, numpy_twin


def generated_body(module: str, name: str):
    """The generated body ``name`` of ``_generated/<module>.py``."""
    return getattr(importlib.import_module(f"transplanter._generated.{module}"), name)


ROOT = Path(__file__).resolve().parents[2]

POSITIVE_INPUTS = ("gears", "train_pitch_curvature", "train_pitch_tangent")
GENERATED_FUNCTIONS = [(module, name) for module in MODULES
                       for name in __import__(f"transplanter._generated.{module}", fromlist=["SIGNATURES"]).SIGNATURES]


# a real gear pair: driver angle within one turn, l > b > 0, m11 > 1/2, a > l + b
PARALLELOGRAM_INPUTS = {
    "driver_angle": lambda rng: rng.uniform(0, 2 * np.pi, size=1),
    "pitch": lambda rng: np.r_[rng.uniform(40, 60), rng.uniform(5, 15), rng.uniform(0.8, 2.0), rng.uniform(0.6, 1.5)],
    "center_distance": lambda rng: rng.uniform(90, 130, size=1),
}

# a pinion cutter: its tip and the lowest radius of its involute (base or root circle) above the base circle
SHAPER_REACH_INPUTS = {
    "pressure_angle": lambda rng: rng.uniform(0.2, 0.45, size=1),
    "cutter_radius": lambda rng: rng.uniform(10, 20, size=1),
    "tip_radius": lambda rng: rng.uniform(21, 25, size=1),
    "lowest_radius": lambda rng: rng.uniform(20, 21, size=1),
}
# a plate link L3 longer than sqrt(m) L4, so that some |BF| gives the margin m (else the band is empty)
CLOSURE_BAND_INPUTS = {
    "chain_lengths": lambda rng: np.r_[rng.uniform(150, 250), rng.uniform(50, 80), rng.uniform(150, 200)],
    "frame_distance": lambda rng: rng.uniform(80, 150, size=1),
    "margin": lambda rng: rng.uniform(0.0, 0.1, size=1),
}
INPUT_DOMAINS = {("cusp", "shaper_reach"): SHAPER_REACH_INPUTS,
                 ("fivebar_closure_band", "fivebar_closure_band"): CLOSURE_BAND_INPUTS}


@pytest.mark.parametrize("module,name", GENERATED_FUNCTIONS)
def test_generated_matches_lambdify(derived, module, name, rng):
    """casadi Function and numpy twin agree with sympy.lambdify of the derivation."""
    d = derived[(module, name)]
    reference = sp.lambdify(d.input_symbols(), [e for _, g in d.outputs for e in g], "numpy")
    body = generated_body(module, name)
    function, twin = casadi_function(body), numpy_twin(body)
    assert function.name_in() == [n for n, _ in d.inputs]
    assert function.name_out() == [n for n, _ in d.outputs]
    for _ in range(4):
        # positive values keep square roots and ratios real (radii, distances, eccentricities < 1, rho' below)
        domain = PARALLELOGRAM_INPUTS if module == "parallelogram" else INPUT_DOMAINS.get((module, name), {})
        groups = [domain[n](rng) if n in domain
                  else rng.uniform(0.1, 1.0, size=len(g)) if module in POSITIVE_INPUTS else rng.normal(size=len(g))
                  for n, g in d.inputs]
        expected = np.array(reference(*np.concatenate(groups)), float)
        via_casadi = np.concatenate([np.asarray(v).ravel() for v in function(*groups)]) \
            if function.n_out() > 1 else np.asarray(function(*groups)).ravel()
        via_numpy = np.concatenate([v.ravel() for v in twin(*groups)])
        scale = max(1.0, np.abs(expected).max())
        assert np.abs(via_casadi - expected).max() <= 1e-11 * scale
        assert np.abs(via_numpy - expected).max() <= 1e-11 * scale


def test_stamp_matches_the_sources():
    for module in MODULES:
        stamp = read_stamp((GENERATED / f"{module}.py").read_text())
        for name, digest in stamp.items():
            if name != "sympy":
                assert hashlib.sha256((ROOT / "derivations" / name).read_bytes()).hexdigest() == digest, name


def _stamped_sympy():
    return read_stamp((GENERATED / f"{MODULES[0]}.py").read_text())["sympy"]


def _other_hash_seed():
    """A PYTHONHASHSEED that differs from this run's (which is random unless the variable fixes it)."""
    return "54321" if os.environ.get("PYTHONHASHSEED") == "12345" else "12345"


@pytest.fixture(scope="module", autouse=True)
def derive_check_under_another_hash_seed():
    """`transplanter derive --check` in a child process under another hash seed, started when this
    module starts so that it runs beside the tests here; the exactness test waits for it."""
    env = {**os.environ, "PYTHONHASHSEED": _other_hash_seed()}
    child = subprocess.Popen([sys.executable, "-m", "transplanter", "derive", "--check"], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, cwd=ROOT)
    yield child
    if child.poll() is None:        # the exactness test did not run: stop the check it did not need
        child.kill()
    child.communicate()


@pytest.fixture(scope="module")
def regenerated(derived):
    """Every generated module rendered in this process from the session's derivations."""
    return {module: build.render(module, [d for (m, _), d in derived.items() if m == module]) for module in MODULES}


@pytest.mark.skipif(sp.__version__ != _stamped_sympy(), reason="exact regeneration needs the stamped sympy")
def test_regeneration_is_exact_and_deterministic(regenerated, derive_check_under_another_hash_seed):
    """Regenerated here and by `transplanter derive --check` under another hash seed, the modules
    are the committed ones byte for byte."""
    for module in MODULES:
        assert regenerated[module] == (GENERATED / f"{module}.py").read_text(), module
    _, stderr = derive_check_under_another_hash_seed.communicate()
    assert derive_check_under_another_hash_seed.returncode == 0, stderr


def test_check_reports_drift(tmp_path, regenerated, monkeypatch, capsys):
    """`python -m derivations.build --check` fails on one changed character and names that module only
    (rendering is the regeneration above, already checked exact)."""
    monkeypatch.setattr(build, "render", lambda module: regenerated[module])
    shutil.copytree(GENERATED, tmp_path / "gen")
    assert build.main(["--check", "--out", str(tmp_path / "gen")]) == 0
    assert capsys.readouterr().out == "generated code is in step with derivations/\n"
    target = tmp_path / "gen" / f"{MODULES[0]}.py"
    target.write_text(target.read_text().replace("    return", "    return  ", 1))
    assert build.main(["--check", "--out", str(tmp_path / "gen")]) == 1
    out, stderr = capsys.readouterr()
    assert out == "" and stderr.count("\n") == 1 and stderr.startswith("transplanter: failed: derive --check: ")
    assert "out of step" in stderr and stderr.rsplit(": ", 1)[1].startswith(f"{MODULES[0]} (")


def test_package_does_not_import_sympy_at_run_time():
    code = ("import sys, transplanter.cli, transplanter.burmester.synthesis, transplanter.burmester.problem, "
            "transplanter.burmester.figures;"
            "from transplanter.burmester.synthesis import synthesize; "
            "from transplanter.burmester.problem import load_problem;"
            "synthesize(load_problem('examples/burmester_5poses.toml'));"
            "sys.exit('sympy' in sys.modules)")
    assert subprocess.run([sys.executable, "-c", code], cwd=ROOT).returncode == 0

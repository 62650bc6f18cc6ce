"""Every third-party module the installed package imports is a runtime dependency in pyproject.toml, so the
README's main-job command (``pip install -e .``, no dev extra) can run: a module only the dev extra brings
(sympy, scipy before it was declared) fails there. The optional extra [cad] is imported by solids/ alone, which
checks it is installed before it imports it."""
import ast
import sys
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
#: import name -> distribution that provides it (Pillow is a dependency of matplotlib, distributed of dask's
#: extra, OCP, the OpenCASCADE binding, of build123d)
PROVIDED_BY = {"PIL": "matplotlib", "distributed": "dask", "OCP": "build123d"}
#: Modules the package imports only where an optional extra is installed (and says so when it is not).
OPTIONAL = {"distributed", "build123d", "OCP"}


def _imported_top_level_modules(folder: Path = ROOT / "src/transplanter", exclude: Path | None = None) -> set[str]:
    names = set()
    for path in folder.rglob("*.py"):
        if exclude is not None and path.is_relative_to(exclude):
            continue
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.Import):
                names |= {alias.name.split(".")[0] for alias in node.names}
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
    return names


def test_every_imported_third_party_module_is_a_runtime_dependency():
    project = tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]
    declared = {entry.split(">")[0].split("=")[0].split("<")[0].strip().lower() for entry in project["dependencies"]}
    third_party = _imported_top_level_modules() - set(sys.stdlib_module_names) - {"transplanter", "__future__"}
    cad = {entry.split(">")[0].strip().lower() for entry in project["optional-dependencies"]["cad"]}
    outside_solids = {name for name in _imported_top_level_modules(exclude=ROOT / "src/transplanter/solids")
                      if PROVIDED_BY.get(name, name).lower() in cad}
    assert not outside_solids, f"the optional extra [cad] imported outside solids/: {sorted(outside_solids)}"
    extras = {entry.split("[")[0].split(">")[0].strip().lower()
              for name, entries in project["optional-dependencies"].items() if name != "dev" for entry in entries}
    missing = {name for name in third_party
               if PROVIDED_BY.get(name, name).lower() not in (declared | extras if name in OPTIONAL else declared)}
    assert not missing, f"imported by src/transplanter but not in [project] dependencies: {sorted(missing)}"

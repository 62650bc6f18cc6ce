"""``scripts/reproduce_published.py`` loaded as a module, for the tests that check its findings or reuse its
printed formulas (the script is not part of the package)."""
import importlib.util
import sys
from pathlib import Path

_path = Path(__file__).resolve().parents[1] / "scripts/reproduce_published.py"
_spec = importlib.util.spec_from_file_location("reproduce_published", _path)
reproduce = sys.modules.setdefault("reproduce_published", importlib.util.module_from_spec(_spec))
_spec.loader.exec_module(reproduce)

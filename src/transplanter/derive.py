"""``transplanter derive``: run derivations/build.py of the source checkout this package comes from."""
from __future__ import annotations

import importlib
import sys
from pathlib import Path

from transplanter.errors import TransplanterError

CHECKOUT = Path(__file__).resolve().parents[2]


def run_build(argv: list[str]) -> int:
    if not (CHECKOUT / "derivations" / "build.py").exists():
        raise TransplanterError("derive needs a source checkout of transplanter (its derivations/ folder), installed "
                                "with `pip install -e .[dev]`; the package at "
                                f"{Path(__file__).resolve().parent} is an install without one")
    sys.path.insert(0, str(CHECKOUT))
    try:
        build = importlib.import_module("derivations.build")
    except ModuleNotFoundError as error:
        raise TransplanterError(f"derive: {error.name} is not installed: it needs `pip install -e .[dev]`") from None
    except SyntaxError as error:
        raise TransplanterError(f"derive: {error.filename}:{error.lineno}: syntax error ({error.msg})") from None
    return build.main(argv)

"""`transplanter derive` meets a broken checkout with one clear line and exit 2, and its
check compares bytes (a generated file with other line endings is drift)."""
import shutil
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture
def checkout_copy(tmp_path, monkeypatch):
    """A copy of derivations/ importable as ``derivations``, with an empty generated folder."""
    shutil.copytree(ROOT / "derivations", tmp_path / "derivations", ignore=shutil.ignore_patterns("__pycache__"))
    (tmp_path / "src" / "transplanter" / "_generated").mkdir(parents=True)
    monkeypatch.syspath_prepend(str(tmp_path))
    for name in [n for n in sys.modules if n == "derivations" or n.startswith("derivations.")]:
        monkeypatch.delitem(sys.modules, name)
    return tmp_path


def test_syntax_error_in_a_derivation_is_one_line(checkout_copy, capsys):
    (checkout_copy / "derivations" / "burmester.py").write_text("def derive(:\n")
    from derivations import build

    assert build.main(["--check"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "derivations/burmester.py:1: syntax error" in err


def test_generated_module_replaced_by_a_folder_is_named(checkout_copy, capsys):
    (checkout_copy / "src" / "transplanter" / "_generated" / "burmester.py").mkdir()
    from derivations import build

    assert build.main([]) == 2
    assert "_generated/burmester.py is not a file" in capsys.readouterr().err


def test_check_compares_bytes(tmp_path, monkeypatch):
    from derivations import build

    monkeypatch.setattr(build, "render", lambda module: f"# {module}\nVALUE = 1\n")
    for module in build.MODULES:
        (tmp_path / f"{module}.py").write_bytes(f"# {module}\nVALUE = 1\n".encode())
    assert build.build(tmp_path, check=True) == []
    (tmp_path / "gears.py").write_bytes(b"# gears\r\nVALUE = 1\r\n")
    assert build.build(tmp_path, check=True) == ["gears"]


"""The examples ship in the wheel and ``transplanter examples DIR`` copies them; ``derive`` in an install
without the source checkout says in one line that it needs one."""
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from transplanter import derive
from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
#: The checkout's example files, as paths relative to examples/.
CHECKOUT_EXAMPLES = sorted(str(path.relative_to(ROOT / "examples")) for path in (ROOT / "examples").rglob("*")
                           if path.suffix in (".toml", ".py"))


def test_the_wheel_holds_every_example(tmp_path):
    """Built as pip builds it (the project's own build backend)."""
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--quiet", "--wheel-dir", str(tmp_path),
                    str(ROOT)], check=True, capture_output=True)
    (wheel,) = tmp_path.glob("transplanter-*.whl")
    names = zipfile.ZipFile(wheel).namelist()
    shipped = sorted(name.removeprefix("transplanter/examples/") for name in names
                     if name.startswith("transplanter/examples/"))
    assert shipped == CHECKOUT_EXAMPLES and len(shipped) > 20


def test_examples_command_copies_them_all(tmp_path, capsys):
    target = tmp_path / "mine"
    assert main(["examples", str(target)]) == 0
    copied = sorted(str(path.relative_to(target)) for path in target.rglob("*") if path.is_file())
    assert copied == CHECKOUT_EXAMPLES
    assert (target / "vegetable_planting.toml").read_bytes() == (ROOT / "examples/vegetable_planting.toml").read_bytes()
    assert f"copied {len(copied)} example files" in capsys.readouterr().out


@pytest.mark.parametrize("kind, words", [("file", "a file is there"), ("copied before", "already holds")])
def test_a_bad_folder_is_one_line_and_exit_2(tmp_path, capsys, kind, words):
    target = tmp_path / "target"
    if kind == "file":
        target.write_text("mine")
    else:
        main(["examples", str(target)])
        capsys.readouterr()
    assert main(["examples", str(target)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"DIR = {target}: {words}" in err


def test_derive_without_a_source_checkout_is_one_line(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(derive, "CHECKOUT", tmp_path)
    assert main(["derive", "--check"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "derive needs a source checkout" in err and str(tmp_path) not in err

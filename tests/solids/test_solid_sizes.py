"""The solids' sizes from the problem files: ``face_width_mm`` in the table that holds the module (fivebar [gears],
parallelogram [gear], gear [pair]), the five-bar's ``[plates] thickness_mm``; the default rules; bad values refused
in one line naming the field (the reverse problem's in [train]); no build123d, no files and a one-line note."""
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from transplanter import fivebar, gears, parallelogram, reverse
from transplanter.errors import ProblemError
from transplanter.solids import part_files
from transplanter.solids.sizes import FACE_WIDTH_MODULES, PLATE_THICKNESS_PIN_DIAMETERS, SolidSizes
from transplanter.solids.step import MISSING_NOTE

ROOT = Path(__file__).resolve().parents[2]
#: command -> its example, its parser and the table that holds the module
COMMANDS = {"fivebar": ("vegetable_planting.toml", fivebar.parse_problem, "gears"),
            "gear": ("gear_ellipse.toml", gears.parse_problem, "pair"),
            "parallelogram": ("onion_transplanter.toml", parallelogram.parse_problem, "gear"),
            "reverse": ("rice_hoe_reverse.toml", reverse.parse_problem, "train")}


def _data(command: str, table: str, **fields) -> dict:
    data = tomllib.loads((ROOT / "examples" / COMMANDS[command][0]).read_text())
    data.setdefault(table, {}).update(fields)
    return data


@pytest.mark.parametrize("command", COMMANDS)
def test_face_width_is_read_where_the_module_is(command):
    _, parse, table = COMMANDS[command]
    assert parse(_data(command, table, face_width_mm=17.5), "x").solid_sizes.face_width_mm == 17.5
    assert parse(_data(command, table), "x").solid_sizes == SolidSizes()


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("value", [0.0, -4.0, "wide"])
def test_a_bad_face_width_names_the_field(command, value):
    _, parse, table = COMMANDS[command]
    with pytest.raises(ProblemError, match=rf"{table}\.face_width_mm = {value!r}: expected a"):
        parse(_data(command, table, face_width_mm=value), "x")


def test_plate_thickness_is_the_fivebars_plates_table():
    sizes = fivebar.parse_problem(_data("fivebar", "plates", thickness_mm=4.5), "x").solid_sizes
    assert sizes == SolidSizes(None, 4.5)
    with pytest.raises(ProblemError, match=r"plates\.thickness_mm = -1\.0: expected a positive length"):
        fivebar.parse_problem(_data("fivebar", "plates", thickness_mm=-1.0), "x")
    with pytest.raises(ProblemError, match=r"plates\.thick = 3: expected no such field here \(known: thickness_mm\)"):
        fivebar.parse_problem(_data("fivebar", "plates", thick=3), "x")
    with pytest.raises(ProblemError, match=r"pair\.thickness_mm = 3: expected no such field"):
        gears.parse_problem(_data("gear", "pair", thickness_mm=3), "x")


def test_default_rules_and_given_sizes():
    assert SolidSizes().face_width(1.5) == pytest.approx(FACE_WIDTH_MODULES * 1.5)
    assert SolidSizes().thickness(8.0) == pytest.approx(PLATE_THICKNESS_PIN_DIAMETERS * 8.0)
    assert SolidSizes(12.0, 5.0).face_width(1.5) == 12.0 and SolidSizes(12.0, 5.0).thickness(8.0) == 5.0
    with pytest.raises(ProblemError, match=r"SolidSizes\.thickness_mm = 0"):
        SolidSizes(thickness_mm=0)


def test_the_command_refuses_a_bad_face_width_in_one_line(tmp_path):
    problem = tmp_path / "pair.toml"
    problem.write_text((ROOT / "examples/gear_ellipse.toml").read_text().replace("module = 2.0",
                                                                                "module = 2.0\nface_width_mm = -2"))
    run = subprocess.run([sys.executable, "-m", "transplanter", "gear", str(problem), "--out", str(tmp_path / "out")],
                         capture_output=True, text=True)
    assert run.returncode == 2 and not run.stdout
    assert run.stderr.count("\n") == 1 and "pair.face_width_mm = -2" in run.stderr
    assert not (tmp_path / "out").exists()


def test_without_the_cad_extra_no_solid_and_a_one_line_note(monkeypatch, tmp_path):
    monkeypatch.setattr(part_files, "cad_installed", lambda: False)
    assert part_files.write_part_solids(tmp_path, gears=[object()], face_width=10.0, module=1.5) == []
    assert part_files.solids_note(10.0, 6.0) == MISSING_NOTE and "\n" not in MISSING_NOTE
    assert list(tmp_path.iterdir()) == []

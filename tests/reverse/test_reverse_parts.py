"""The reverse train's parts for the workshop as the five-bar's: drawings.pdf (a page per gear sheet), parts.csv (a
row per gear with its teeth, module and keyed bore), the gears' face width in design.toml read back; the pick-up
arm's note names the reverse problem's own fields."""
from __future__ import annotations

import csv
import dataclasses
import re
from pathlib import Path

import pytest

from transplanter.reverse import evaluate_design, load_design
from transplanter.reverse.gear_files import gear_bores
from transplanter.reverse.problem import load_problem
from transplanter.solids.sizes import FACE_WIDTH_MODULES, SolidSizes

ROOT = Path(__file__).resolve().parents[2]
RICE = ROOT / "examples" / "rice_hoe_reverse.toml"
GEARS = ("sun", "first_intermediate", "second_intermediate", "planet")


def test_parts_list_has_a_row_per_gear_and_the_pdf_a_page_per_sheet(rice_result, tmp_path):
    written = {path.name for path in rice_result.write_files(tmp_path, solids=False)}
    assert {"drawings.pdf", "parts.csv"} <= written
    assert not any(name.endswith(".step") for name in written)
    pages = re.findall(rb"/Type\s*/Page\b(?!s)", (tmp_path / "drawings.pdf").read_bytes())
    assert len(pages) == len(GEARS)
    with (tmp_path / "parts.csv").open() as stream:
        rows = list(csv.DictReader(stream))
    toothed, bores = rice_result.toothed, gear_bores(rice_result.toothed)
    teeth = dict(zip(GEARS, [toothed.counts[0]] * 2 + [toothed.counts[1]] * 2, strict=True))
    assert [row["part"] for row in rows] == list(GEARS)
    for row in rows:
        assert int(row["teeth"]) == teeth[row["part"]] and float(row["module_mm"]) == toothed.module
        assert row["key_dimensions_mm"].startswith(f"bore {bores[row['part']].diameter:g}; key ")


@pytest.mark.parametrize("given, written", [(None, FACE_WIDTH_MODULES * 1.5), (12.5, 12.5)])
def test_face_width_is_written_to_the_design_and_read_back(rice_result, tmp_path, given, written):
    sized = dataclasses.replace(rice_result.problem, solid_sizes=SolidSizes(given))
    result = dataclasses.replace(rice_result, problem=sized)
    result.write_files(tmp_path, solids=False)
    assert re.search(rf"^face_width_mm = {written}$", (tmp_path / "design.toml").read_text(), re.M)
    design = load_design(tmp_path / "design.toml")
    assert design.solid_sizes == SolidSizes(written)
    again = evaluate_design(load_problem(RICE), design, tolerance=False)
    assert again.problem.solid_sizes.face_width(again.toothed.module) == written
    assert again.to_json()["solids"] == result.to_json()["solids"]


def test_the_pickup_arms_note_names_the_reverse_problems_fields(pickup_result):
    assert pickup_result.toothed is None
    assert "train.center_distances[0] = 90:" in pickup_result.teeth_note and "gears." not in pickup_result.teeth_note

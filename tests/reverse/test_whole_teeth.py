"""The reverse train with whole teeth, made as the five-bar's: whole counts on a bent carrier, teeth that mesh
over a turn, the gear sheets and pitch-curve tables in --out; centre distances without whole counts say why."""
from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import ezdxf
import numpy as np
import pytest
import shapely

from transplanter.cli import main
from transplanter.drawing.sheet import LAYERS
from transplanter.reverse import synthesize
from transplanter.reverse.problem import load_problem

RICE = Path(__file__).parents[2] / "examples" / "rice_hoe_reverse.toml"
GEARS = ("sun", "first_intermediate", "second_intermediate", "planet")


def test_rice_train_has_whole_teeth_on_a_bent_carrier_that_mesh(rice_result):
    toothed, s = rice_result.toothed, rice_result.motion.carrier_length
    assert rice_result.failures == [] and toothed.passed
    a1, a2 = toothed.train.center_distances
    assert abs(a1 - a2) <= s <= a1 + a2 and a1 + a2 > s * (1 + 1e-6)         # the carrier is bent
    for stage, count in zip((toothed.train.stage_one, toothed.train.stage_two), toothed.counts, strict=True):
        for perimeter in stage.perimeters:           # each pitch curve carries the whole count at the module
            assert perimeter / (np.pi * toothed.module) == pytest.approx(count, rel=1e-9)
    assert max(check.max_overlap_mm for check in toothed.mesh) < 0.005 * toothed.module
    shaft = toothed.shaft
    assert np.hypot(*shaft) == pytest.approx(a1, rel=1e-12)
    assert np.hypot(shaft[0] - s, shaft[1]) == pytest.approx(a2, rel=1e-12)
    reach = s + rice_result.motion.arm_length
    assert rice_result.verification.max_error_mm < 1e-8 * reach                 # rolled on the chosen centres


def test_rice_gears_cut_outlines_that_do_not_cross_themselves(rice_result):
    """The sun's and second intermediate's pitch curves have hollow corners (the first intermediate's and planet's
    matching ones bulge), and the planet bends near the rack's undercut limit: the tip and root curves offset
    from such a curve cross themselves there, and a flank turns back before the root; every outline must still
    be a simple closed curve."""
    for teeth in rice_result.toothed.teeth:
        for outline in teeth.outlines:
            assert shapely.is_simple(shapely.linearrings(outline)) and shapely.Polygon(outline).is_valid
        assert teeth.self_intersections == (0, 0)


def test_a_tooth_outline_that_crosses_itself_fails_the_run(tmp_path, capsys, monkeypatch):
    from transplanter.trains import toothed_train

    cut = toothed_train.generate_teeth

    def with_a_crossing_driven(*args, **kwargs):        # each stage's driven outline said to cross itself once
        return dataclasses.replace(cut(*args, **kwargs), self_intersections=(0, 1))

    monkeypatch.setattr(toothed_train, "generate_teeth", with_a_crossing_driven)
    code = main(["reverse", str(RICE), "--no-tolerance", "--no-step", "--json", "--out", str(tmp_path)])
    captured = capsys.readouterr()
    report = json.loads(captured.out)
    assert code == 1 and report["status"] == "FAILED" and len(captured.err.strip().splitlines()) == 1
    assert [g["self_intersections"] for g in report["toothed_train"]["gears"]] == [0, 1, 0, 1]
    assert report["failures"] == ["first intermediate: its tooth outline crosses itself (1 crossings)",
                                  "planet: its tooth outline crosses itself (1 crossings)"]
    assert report["toothed_train"]["mesh_check"]["passed"] is True


def test_out_has_gear_sheets_and_pitch_curves_listed_in_the_report(tmp_path, capsys, rice_result_from_synthesize):
    """The command's own --out of the file (its train the session's ``rice_result``, read above)."""
    assert main(["reverse", str(RICE), "--no-tolerance", "--no-step", "--json", "--out", str(tmp_path)]) == 0
    report = json.loads(capsys.readouterr().out)
    listed = {name for names in report["files"].values() for name in names}
    toothed = report["toothed_train"]
    for name, teeth in zip(GEARS, np.repeat(toothed["teeth"], 2), strict=True):
        assert {f"{name}.dxf", f"{name}.svg", f"pitch_curve_{name}.csv"} <= listed
        doc = ezdxf.readfile(tmp_path / f"{name}.dxf")
        assert {layer.dxf.name for layer in doc.layers} >= set(LAYERS) and doc.header["$INSUNITS"] == 4
        table = np.loadtxt(tmp_path / f"pitch_curve_{name}.csv", delimiter=",", skiprows=1)
        closed = np.r_[table[:, 2:], table[:1, 2:]]
        perimeter = np.linalg.norm(np.diff(closed, axis=0), axis=1).sum()      # the polygon, a hair short
        assert perimeter / (np.pi * toothed["module"]) == pytest.approx(teeth, rel=1e-4)
    assert toothed["mesh_check"]["passed"] and toothed["mesh_check"]["max_overlap_mm"] < 0.005 * toothed["module"]
    design = (tmp_path / "design.toml").read_text()
    assert f"center_distances = {toothed['center_distances_mm']}".replace("'", "") in design


def test_gear_files_are_the_same_bytes_when_written_again(rice_result, tmp_path):
    first = rice_result.write_files(tmp_path / "one", solids=False)
    second = rice_result.write_files(tmp_path / "two", solids=False)
    assert [p.name for p in first] == [p.name for p in second]
    assert all(a.read_bytes() == b.read_bytes() for a, b in zip(first, second, strict=True))


def test_centre_distances_without_whole_teeth_keep_the_train_and_say_why():
    problem = load_problem(RICE)
    given = dataclasses.replace(problem, center_distances=(46.15, 46.15))
    result = synthesize(given, tolerance=False)
    assert result.toothed is None and "teeth at module 1.5; expected whole teeth" in result.teeth_note
    assert result.train.center_distances == (46.15, 46.15) and result.failures == []

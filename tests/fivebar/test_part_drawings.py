"""The five-bar's part drawings, assembly, PDF and parts list, read back: the same bytes on every run, every
dimension the design's length, and the bores checked against the teeth."""
import csv
from dataclasses import replace

import ezdxf
import numpy as np
import pytest
import shapely

from transplanter.drawing.sheet import LAYERS
from transplanter.fivebar.drawings import write_drawings
from transplanter.fivebar.report import fivebar_result_json
from transplanter.fivebar.shaft_spec import ShaftSpec
from transplanter.fivebar.shafts import shaft_torques
from transplanter.shafts.sizing import diameter_for_pin
from transplanter.solids.sizes import SolidSizes

PARTS = ("carrier", "rod_AF", "push_plate_EFP", "receiving_plate_BE")
GEARS = ("sun", "first_intermediate", "second_intermediate", "planet")


@pytest.fixture(scope="module")
def folders(example_result, example_result_drawings, tmp_path_factory):
    """The drawings written twice, as two runs of the main job write them: the session's, and again here."""
    again = tmp_path_factory.mktemp("run2")
    write_drawings(example_result, again)
    return [example_result_drawings[0].parent, again]


def test_two_runs_write_the_same_bytes(folders):
    first, second = folders
    names = sorted(path.name for path in first.iterdir() if path.suffix in (".dxf", ".pdf", ".csv", ".svg"))
    assert {f"{name}.dxf" for name in (*PARTS, *GEARS, "linkage")} <= set(names)
    assert "drawings.pdf" in names and "parts.csv" in names
    for name in names:
        assert (first / name).read_bytes() == (second / name).read_bytes(), name


def test_part_dimensions_are_the_reports_lengths(example_result, folders):
    report = fivebar_result_json(example_result)
    design, (a1, a2) = report["design"], report["gear_train"]["center_distances_mm"]
    expected = {
        "carrier": [design["carrier_length_OA"], a1, a2],
        "rod_AF": [design["rod_length_AF"]],
        "push_plate_EFP": [design["plate_link_length_EF"], design["push_plate_EP"], design["push_plate_FP"]],
        "receiving_plate_BE": [design["receiving_plate_length_BE"]],
    }
    diameters = {name: shaft["diameter_mm"] for name, shaft in report["shafts"]["shafts"].items()}
    holes = {"carrier": [diameters["sun"], diameters["planet"], diameters["intermediate"]],
             "rod_AF": [diameters["planet"], diameters["hinge"]], "push_plate_EFP": [diameters["hinge"]] * 2,
             "receiving_plate_BE": [diameters["hinge"]] * 2}
    for name in PARTS:
        space = ezdxf.readfile(folders[0] / f"{name}.dxf").modelspace()
        aligned = sorted(d.get_measurement() for d in space.query("DIMENSION") if d.dimtype == 0)
        assert np.abs(np.array(aligned) - sorted(expected[name])).max() < 1e-6, name
        measured_holes = sorted(d.get_measurement() for d in space.query("DIMENSION") if d.dimtype == 3)
        assert np.abs(np.array(measured_holes) - sorted(holes[name])).max() < 1e-9, name
        assert sorted(2 * c.dxf.radius for c in space.query("CIRCLE[layer=='BORE']")) == sorted(holes[name])


def test_every_dimension_line_stands_clear_of_its_part(folders):
    """Each centre distance is drawn outside the plate, not across it (read back: the dimension line, from the
    DIMENSION's definition points, against the OUTLINE polygon)."""
    for name in PARTS:
        space = ezdxf.readfile(folders[0] / f"{name}.dxf").modelspace()
        outline = shapely.Polygon(space.query("LWPOLYLINE[layer=='OUTLINE']")[0].get_points("xy"))
        for dimension in (d for d in space.query("DIMENSION") if d.dimtype == 0):
            first, second, at = (np.array(dimension.dxf.get(point))[:2]
                                 for point in ("defpoint2", "defpoint3", "defpoint"))
            shift = at - second
            line = shapely.LineString([first + shift, second + shift])
            assert line.distance(outline) > 0, (name, dimension.get_measurement())


def test_every_five_bar_sheet_has_the_conventions_layers(folders):
    for path in sorted(folders[0].glob("*.dxf")):
        document = ezdxf.readfile(path)
        assert {layer.dxf.name for layer in document.layers} == {"0", "Defpoints", *LAYERS}, path.name
        assert {entity.dxf.layer for entity in document.modelspace()} <= set(LAYERS), path.name


def test_parts_list_has_every_part_with_teeth_for_the_gears(example_result, folders):
    with (folders[0] / "parts.csv").open() as stream:
        rows = list(csv.DictReader(stream))
    assert [row["part"] for row in rows] == [*PARTS, *GEARS]
    teeth = {gear.name.replace(" ", "_"): gear.teeth for gear in example_result.toothed.gears}
    for row in rows:
        assert row["material"] == "" and row["quantity"] == "1"
        assert row["teeth"] == (str(teeth[row["part"]]) if row["part"] in GEARS else "")
    assert folders[0].joinpath("drawings.pdf").read_bytes()[:5] == b"%PDF-"


def test_shaft_torques_balance_power_through_the_train(example_result):
    """A lossless train: the intermediate shaft's power equals the sun's (rates by finite differences of the
    train's own turn map, not its polynomial rate), and the default shafts carry their peak torque."""
    loads, train = example_result.loads, example_result.train
    torques = shaft_torques(example_result.toothed, loads)
    step = 1e-6
    inside = (loads.turns > step) & (loads.turns < 2 * np.pi - step)
    turns = loads.turns[inside]
    psi_rate = (train.intermediate_turn(turns + step) - train.intermediate_turn(turns - step)) / (2 * step)
    assert np.allclose(torques["intermediate"][inside] * psi_rate, torques["sun"][inside], rtol=1e-6,
                       atol=1e-9 * np.abs(torques["sun"]).max())
    for shaft in example_result.shafts.shafts.values():
        if shaft.peak_torque_nm is not None:
            assert 16 * shaft.peak_torque_nm * 1e3 / (np.pi * shaft.diameter**3) <= 20.0


def test_hinge_pins_are_sized_by_the_largest_force_at_b_e_and_f(example_result):
    """The pins carry the largest force on B, E or F over the turn (the loads' own hinge forces), on the plates'
    thickness: the default one, then a given one."""
    loads = example_result.loads
    force = max(np.hypot(*loads.hinge_forces[name].T).max() for name in "BEF")
    pin = example_result.shafts.shafts["hinge"]
    assert pin.peak_force_n == pytest.approx(force, rel=1e-12)
    assert pin.diameter == diameter_for_pin(force)
    thin = replace(example_result.problem, solid_sizes=SolidSizes(thickness_mm=0.5))
    assert replace(example_result, problem=thin).shafts.shafts["hinge"].diameter == diameter_for_pin(force, 0.5)
    given = replace(example_result.problem, shafts=ShaftSpec({"hinge": 12.0}))
    assert replace(example_result, problem=given).shafts.shafts["hinge"].diameter == 12.0


def test_a_bore_that_reaches_the_teeth_fails_with_the_numbers(example_result):
    root = example_result.shafts.roots["sun"]
    too_big = float(2 * int(root))      # a shaft as wide as the sun's root circle
    problem = replace(example_result.problem, shafts=ShaftSpec({"sun": too_big}))
    result = replace(example_result, problem=problem)
    failures = [text for text in result.failures if "bore" in text]
    assert len(failures) == 1 and failures[0].startswith("sun bore")
    assert f"{too_big:g} mm bore" in failures[0] and f"{root:.3f}" in failures[0]
    assert not example_result.shafts.failures

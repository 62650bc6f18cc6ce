"""The one drawing convention: layers with a colour each, millimetres, a title block, the same bytes on every run."""
import ezdxf
import numpy as np

from transplanter import __version__
from transplanter.drawing.sheet import LAYERS, Sheet, TitleBlock

DXF_MM = 4          # $INSUNITS code of millimetres


def _sheet() -> Sheet:
    sheet = Sheet()
    sheet.polyline(np.array([[0.0, 0.0], [80.0, 0.0], [80.0, 30.0]]), "OUTLINE", close=True)
    sheet.circle((0.0, 0.0), 5.0, "BORE")
    sheet.aligned_dimension((0.0, 0.0), (80.0, 30.0), 10.0)
    sheet.linear_dimension((0.0, 0.0), (80.0, 30.0), (0.0, 40.0), 0.0)
    sheet.diameter_dimension((0.0, 0.0), 5.0, 45.0)
    sheet.title_block(TitleBlock("test plate", 2, "a problem", module=1.5, teeth=31, pressure_angle_deg=20.0,
                                 center_distance_mm=61.25))
    return sheet


def test_two_sheets_of_the_same_part_are_the_same_bytes(tmp_path):
    first, second = _sheet().save(tmp_path / "a.dxf"), _sheet().save(tmp_path / "b.dxf")
    assert first.read_bytes() == second.read_bytes()
    # ezdxf's own switch is left as it was found
    assert not ezdxf.options.write_fixed_meta_data_for_testing


def test_sheet_reads_back_in_millimetres_with_every_layer_coloured(tmp_path):
    document = ezdxf.readfile(_sheet().save(tmp_path / "a.dxf"))
    assert document.header["$INSUNITS"] == DXF_MM
    colours = {layer.dxf.name: layer.color for layer in document.layers if layer.dxf.name in LAYERS}
    assert colours == LAYERS
    assert len(set(colours.values())) == len(LAYERS)


def test_dimensions_measure_what_was_dimensioned(tmp_path):
    space = ezdxf.readfile(_sheet().save(tmp_path / "a.dxf")).modelspace()
    measured = sorted(dimension.get_measurement() for dimension in space.query("DIMENSION"))
    assert np.allclose(measured, sorted([np.hypot(80.0, 30.0), 80.0, 10.0]), rtol=0, atol=1e-12)
    assert {dimension.dxf.layer for dimension in space.query("DIMENSION")} == {"DIMENSIONS"}


def test_title_block_names_the_part_its_gear_data_and_the_version(tmp_path):
    space = ezdxf.readfile(_sheet().save(tmp_path / "a.dxf")).modelspace()
    texts = [text.dxf.text for text in space.query("TEXT[layer=='TEXT']")]
    for expected in ("test plate", "2", "1.5 mm", "31", "20 deg", "61.2500 mm", "a problem", "material"):
        assert expected in texts
    assert any(__version__ in text for text in texts)
    # the block sits below every piece of geometry
    lowest_text = min(text.dxf.insert[1] for text in space.query("TEXT[layer=='TEXT']"))
    assert lowest_text < -5.0


def test_a_part_that_is_not_a_gear_leaves_the_gear_rows_out():
    names = [name for name, _ in TitleBlock("rod AF", 1, "a problem").rows()]
    assert "module" not in names and "teeth" not in names and "material" in names

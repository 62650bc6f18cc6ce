"""drawings.pdf: a page per sheet, every text of a sheet as text in the PDF, the same bytes twice; the sheet
renderer's geometry against the sheet's own entities."""
import re
import zlib

import numpy as np
import pytest

from transplanter.drawing.pdf import write_pdf
from transplanter.drawing.sheet import LAYERS, Sheet, TitleBlock
from transplanter.drawing.sheet_page import ARC_STEP_DEG, Ink, collect


def _sheet(label: str) -> Sheet:
    """A sheet with one entity of every kind the package draws, its texts naming ``label``."""
    sheet = Sheet()
    sheet.polyline(np.array([[0.0, 0.0], [80.0, 0.0], [80.0, 40.0], [0.0, 40.0]]), "OUTLINE", close=True)
    sheet.polyline(np.array([[10.0, 10.0], [70.0, 30.0]]), "PITCH")
    sheet.circle((20.0, 20.0), 5.0, "BORE")
    sheet.arc((60.0, 20.0), 6.0, 30.0, 300.0, "BORE")
    sheet.center_cross((20.0, 20.0), 14.0)
    sheet.text(f"hinge {label}", (25.0, 25.0))
    sheet.text("%%c10 bore, 20%%d", (25.0, 35.0))                    # DXF control codes: Ø and °
    sheet.aligned_dimension((20.0, 20.0), (60.0, 20.0), -30.0)
    sheet.diameter_dimension((20.0, 20.0), 5.0, 225.0)
    sheet.title_block(TitleBlock(f"part {label}", 2, "a test problem"))
    return sheet


def _shown_texts(path) -> list[str]:
    """Every string the PDF's page streams show (``(...) Tj``), PDF escapes undone."""
    data = path.read_bytes()
    texts = []
    for stream in re.findall(rb"stream\r?\n(.*?)\r?\nendstream", data, re.S):
        try:
            content = zlib.decompress(stream)
        except zlib.error:
            continue
        for raw in re.findall(rb"\(((?:\\.|[^\\)])*)\)\s*Tj", content, re.S):
            texts.append(re.sub(rb"\\([()\\])", rb"\1", raw).decode("cp1252"))
    return texts


@pytest.fixture(scope="module")
def sheets():
    return [(f"{label}.dxf", _sheet(label).document) for label in ("first", "second", "third")]


def test_one_page_per_sheet_with_the_sheets_texts_as_text(sheets, tmp_path):
    path = write_pdf(sheets, tmp_path / "drawings.pdf")
    assert len(re.findall(rb"/Type\s*/Page\b(?!s)", path.read_bytes())) == len(sheets)
    shown = _shown_texts(path)
    for name, document in sheets:
        expected = [entity.plain_text() for entity in document.modelspace().query("TEXT")]
        expected += [text.plain_text() for dimension in document.modelspace().query("DIMENSION")
                     for text in dimension.virtual_entities() if text.dxftype() == "MTEXT"]
        assert f"{name} (millimetres)" in shown
        assert {"40", "Ø10", "Ø10 bore, 20°"} <= set(expected)      # the dimensions' texts, control codes read
        assert set(expected) - {""} <= set(shown)          # the title block's blank material shows nothing


def test_the_same_sheets_give_the_same_bytes(sheets, tmp_path):
    first = write_pdf(sheets, tmp_path / "first.pdf").read_bytes()
    assert write_pdf(sheets, tmp_path / "second.pdf").read_bytes() == first


def test_every_entity_is_drawn_in_its_layers_colour_and_line_type(sheets):
    document = sheets[0][1]
    ink = collect(document.modelspace(), document, Ink())
    by_colour = {colour: [line for (c, _, _), lines in ink.lines.items() if c == colour for line in lines]
                 for colour in LAYERS.values()}
    outline = [line for line in by_colour[LAYERS["OUTLINE"]] if len(line) == 5]
    assert len(outline) == 1 and np.array_equal(outline[0][0], outline[0][-1])      # closed
    bore_distances = [np.hypot(*(line - center).T) for line in by_colour[LAYERS["BORE"]]
                      for center, radius in (((20.0, 20.0), 5.0), ((60.0, 20.0), 6.0))
                      if np.allclose(np.hypot(*(line - center).T), radius)]
    assert len(bore_distances) == 2
    arc = next(line for line in by_colour[LAYERS["BORE"]] if np.allclose(np.hypot(*(line - (60.0, 20.0)).T), 6.0))
    ends = np.degrees(np.arctan2(*(arc[[0, -1]] - (60.0, 20.0)).T[::-1])) % 360
    assert np.allclose(ends, [30.0, 300.0]) and len(arc) >= 270 / ARC_STEP_DEG
    linetypes = {linetype for (colour, linetype, _) in ink.lines if colour == LAYERS["PITCH"]}
    assert linetypes == {"DASHED"}
    # the dimensions' lines, ticks and texts take the DIMENSIONS layer (block entities on layer 0)
    dimension = LAYERS["DIMENSIONS"]
    assert {(colour, width > 0) for (colour, _, width) in ink.lines if colour == dimension} == {
        (dimension, False), (dimension, True)}
    assert {text[0] for text in ink.texts if text[-1] == dimension} == {"40", "Ø10"}
    assert {text[0] for text in ink.texts if text[-1] == LAYERS["TEXT"]} >= {"hinge first", "part first"}


def test_an_entity_the_renderer_does_not_know_is_refused():
    sheet = Sheet()
    sheet.space.add_ellipse((0.0, 0.0), major_axis=(2.0, 0.0), ratio=0.5)
    with pytest.raises(ValueError, match="ELLIPSE"):
        collect(sheet.space, sheet.document, Ink())

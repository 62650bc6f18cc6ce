"""One DXF sheet in the project's convention: millimetres (INSUNITS), every sheet with the same layers, each
with its own colour (AutoCAD colour index), a title block, and the same bytes on every run.

Layers: OUTLINE (what is cut), PITCH (pitch curves, dashed), BORE (bores and hinge holes), KEYWAY (hub
keyways), MARK (assembly marks), CENTERLINES (centre crosses, link centre lines, paths: construction, dash-dot),
DIMENSIONS (ezdxf linear, aligned and diameter dimensions) and TEXT (labels and the title block).
"""
from __future__ import annotations

from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import ezdxf
import numpy as np
from ezdxf.entities.lwpolyline import LWPolylinePoints

#: Layer -> AutoCAD colour index.
LAYERS = {"OUTLINE": 7, "PITCH": 5, "BORE": 1, "KEYWAY": 6, "MARK": 3, "CENTERLINES": 4, "DIMENSIONS": 30,
          "TEXT": 8}
LINETYPES = {"PITCH": "DASHED", "CENTERLINES": "CENTER"}
#: Text height as a fraction of the sheet's geometry span, and the title block's row height in text heights.
TEXT_FRACTION = 0.02
ROW_HEIGHTS = 1.8
#: A character's width as a fraction of the text height (the title block's columns fit their longest text).
CHARACTER_WIDTH = 0.8
#: Dimension text as a fraction of the text height.
DIMENSION_TEXT = 0.8


@dataclass(frozen=True)
class TitleBlock:
    """What the title block says of a part; gear fields are None for other parts, material is left blank."""

    part: str
    quantity: int
    problem_title: str
    module: float | None = None
    teeth: int | None = None
    pressure_angle_deg: float | None = None
    center_distance_mm: float | None = None
    material: str = ""

    def rows(self) -> list[tuple[str, str]]:
        from transplanter import __version__

        gear = [("module", self.module, "{:g} mm"), ("teeth", self.teeth, "{}"),
                ("pressure angle", self.pressure_angle_deg, "{:g} deg"),
                ("centre distance", self.center_distance_mm, "{:.4f} mm")]
        return [("part", self.part), ("quantity", str(self.quantity)),
                *[(name, form.format(value)) for name, value, form in gear if value is not None],
                ("material", self.material), ("problem", self.problem_title),
                ("drawn by", f"transplanter {__version__}; millimetres")]


class Sheet:
    """A DXF document with the layers above; geometry added through it widens the span the text scales with."""

    def __init__(self):
        with _fixed_metadata():
            self.document = ezdxf.new("R2010", setup=["linetypes", "dimstyles"], units=ezdxf.units.MM)
        for name, colour in LAYERS.items():
            self.document.layers.add(name, color=colour, linetype=LINETYPES.get(name, "Continuous"))
        self.space = self.document.modelspace()
        self.low, self.high = np.full(2, np.inf), np.full(2, -np.inf)

    def _widen(self, points) -> None:
        points = np.atleast_2d(np.asarray(points, float))
        self.low, self.high = np.minimum(self.low, points.min(axis=0)), np.maximum(self.high, points.max(axis=0))

    @property
    def text_height(self) -> float:
        return TEXT_FRACTION * float(np.max(self.high - self.low))

    def polyline(self, points: np.ndarray, layer: str, close: bool = False) -> None:
        """An LWPOLYLINE of ``points`` (N, 2) mm with its vertex array filled at once: ezdxf's ``add_lwpolyline``
        appends point by point, each a copy of the array so far (16 s for the four outlines of a 100-tooth
        composite pair, against 0.1 s this way)."""
        points = np.asarray(points, float)
        polyline = self.space.add_lwpolyline([], close=close, dxfattribs={"layer": layer})
        polyline.lwpoints = LWPolylinePoints(np.c_[points, np.zeros((len(points), 3))].tolist())
        self._widen(points)

    def line(self, start, end, layer: str) -> None:
        self.space.add_line(np.asarray(start, float).tolist(), np.asarray(end, float).tolist(),
                            dxfattribs={"layer": layer})
        self._widen([start, end])

    def circle(self, center, radius: float, layer: str) -> None:
        center = np.asarray(center, float)
        self.space.add_circle(center.tolist(), float(radius), dxfattribs={"layer": layer})
        self._widen([center - radius, center + radius])

    def arc(self, center, radius: float, start_deg: float, end_deg: float, layer: str) -> None:
        """Counterclockwise from ``start_deg`` to ``end_deg``."""
        center = np.asarray(center, float)
        self.space.add_arc(center.tolist(), float(radius), start_deg, end_deg, dxfattribs={"layer": layer})
        self._widen([center - radius, center + radius])

    def text(self, text: str, at, height: float | None = None) -> None:
        self.space.add_text(text, height=height or self.text_height,
                            dxfattribs={"layer": "TEXT", "insert": np.asarray(at, float).tolist()})

    def center_cross(self, center, size: float) -> None:
        """Two centre lines of ``size`` mm through ``center``."""
        center = np.asarray(center, float)
        for axis in np.eye(2):
            self.line(center - size / 2 * axis, center + size / 2 * axis, "CENTERLINES")

    def aligned_dimension(self, p1, p2, offset: float) -> None:
        """The distance p1-p2, drawn ``offset`` mm to the left of p1 -> p2; the sheet's extent takes in its line
        and text, so the title block stays below them."""
        p1, p2 = np.asarray(p1, float), np.asarray(p2, float)
        style = self._dimension_style()
        self.space.add_aligned_dim(p1=p1.tolist(), p2=p2.tolist(), distance=offset, override=style,
                                   dxfattribs={"layer": "DIMENSIONS"}).render()
        left = np.array([p1[1] - p2[1], p2[0] - p1[0]]) / np.hypot(*(p2 - p1))
        reach = offset + np.copysign(2 * style["dimtxt"], offset)
        self._widen([p1 + reach * left, p2 + reach * left])

    def linear_dimension(self, p1, p2, base, angle_deg: float) -> None:
        """The distance p1-p2 measured along ``angle_deg`` (0: horizontal), its line through ``base``."""
        self.space.add_linear_dim(base=np.asarray(base, float).tolist(), p1=np.asarray(p1, float).tolist(),
                                  p2=np.asarray(p2, float).tolist(), angle=angle_deg,
                                  override=self._dimension_style(), dxfattribs={"layer": "DIMENSIONS"}).render()

    def diameter_dimension(self, center, radius: float, angle_deg: float) -> None:
        self.space.add_diameter_dim(center=np.asarray(center, float).tolist(), radius=float(radius),
                                    angle=angle_deg, override=self._dimension_style(),
                                    dxfattribs={"layer": "DIMENSIONS"}).render()

    def _dimension_style(self) -> dict:
        height = self.text_height * DIMENSION_TEXT
        # ezdxf's dimension styles scale the text by 100 (drawing units of m, text in cm): 1 here, mm to mm
        return {"dimtxt": height, "dimasz": height, "dimexe": height / 2, "dimexo": height / 2, "dimdec": 3,
                "dimlfac": 1.0}

    def title_block(self, title: TitleBlock) -> None:
        """Two columns of rows below the geometry, on TEXT: a frame, the names and the values."""
        height = self.text_height
        rows = title.rows()
        longest = [max(len(texts[column]) for texts in rows) for column in (0, 1)]
        row, widths = ROW_HEIGHTS * height, tuple(CHARACTER_WIDTH * height * (count + 2) for count in longest)
        top, left = self.low[1] - 2 * row, self.low[0]
        bottom = top - row * len(rows)
        right = left + sum(widths)
        frame = [(left, top), (right, top), (right, bottom), (left, bottom)]
        self.space.add_lwpolyline(frame, close=True, dxfattribs={"layer": "TEXT"})
        self.space.add_line((left + widths[0], top), (left + widths[0], bottom), dxfattribs={"layer": "TEXT"})
        for index, (name, value) in enumerate(rows):
            y = top - row * (index + 1)
            if index:
                self.space.add_line((left, y + row), (right, y + row), dxfattribs={"layer": "TEXT"})
            for x, text in ((left, name), (left + widths[0], value)):
                self.text(text, (x + height / 2, y + (row - height) / 2), height)

    def save(self, path: Path) -> Path:
        """Write the DXF with ezdxf's fixed header times and GUIDs: the same design gives the same bytes."""
        with _fixed_metadata():
            self.document.saveas(path)
        return path


@contextmanager
def _fixed_metadata():
    """ezdxf's own switch for fixed creation/update times, GUIDs and marker string, set only while a sheet is
    made and saved."""
    before = ezdxf.options.write_fixed_meta_data_for_testing
    ezdxf.options.write_fixed_meta_data_for_testing = True
    try:
        yield
    finally:
        ezdxf.options.write_fixed_meta_data_for_testing = before

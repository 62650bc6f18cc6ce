"""One DXF sheet drawn on a matplotlib Figure for the PDF: lines, polylines, arcs, circles and the dimensions' lines
and ticks as one LineCollection per colour, line type and width, texts as text (a PDF reader finds and copies
them), in the layers' colours and line types, to scale with equal axes.

Dimensions and block references are drawn through ezdxf's virtual entities; an entity on layer 0 of a block takes
the reference's layer and a BYBLOCK colour its colour, as CAD programs draw them. The Defpoints layer is not
drawn.
"""
from __future__ import annotations

from collections import defaultdict
from dataclasses import dataclass, field

import numpy as np
from ezdxf.colors import aci2rgb
from ezdxf.document import Drawing
from ezdxf.entities import DXFGraphic
from matplotlib.collections import LineCollection
from matplotlib.figure import Figure
from matplotlib.lines import Line2D
from matplotlib.transforms import Affine2D

#: Line width (pt) of lines without a width of their own: 0.25 mm, the DXF default lineweight.
LINE_WIDTH = 0.7
#: Dash patterns (pt) of the sheet's line types; others are drawn solid.
DASHES = {"DASHED": (0.0, (6.0, 3.0)), "CENTER": (0.0, (12.0, 3.0, 3.0, 3.0))}
#: Chord angle (deg) of arcs and circles drawn as polylines.
ARC_STEP_DEG = 2.0
#: The PDF's font, one of the 14 every PDF reader has (not embedded), and its weight as its metrics name it.
FONT = {"family": "Helvetica", "weight": "medium"}
#: DXF text height is the capital letters' height; matplotlib's font size is the em: Helvetica's cap height.
CAP_HEIGHT_EM = 0.718
#: A DXF TEXT's horizontal alignment (halign 0, 1, 2) and MTEXT's attachment point (1-9) in matplotlib's words.
TEXT_ALIGNMENT = {0: "left", 1: "center", 2: "right"}
ATTACHMENT = {1: ("left", "top"), 2: ("center", "top"), 3: ("right", "top"),
              4: ("left", "center"), 5: ("center", "center"), 6: ("right", "center"),
              7: ("left", "bottom"), 8: ("center", "bottom"), 9: ("right", "bottom")}
MIRRORED = {"left": "right", "right": "left", "top": "bottom", "bottom": "top", "center": "center"}
BYBLOCK, BYLAYER = 0, 256
#: ACI 7 is white on a dark screen, black on paper.
PAPER_WHITE = 7


@dataclass(frozen=True)
class Pen:
    """The layer, AutoCAD colour index and line type an entity is drawn with, BYLAYER and BYBLOCK resolved."""

    layer: str
    colour: int
    linetype: str


@dataclass
class Ink:
    """What a sheet puts on paper: polylines (N, 2) mm by (colour, line type, width in mm or 0), points (2,) mm
    by colour, and texts (text, insertion (2,) mm, height mm, rotation deg, horizontal and vertical alignment,
    colour)."""

    lines: dict[tuple[int, str, float], list[np.ndarray]] = field(default_factory=lambda: defaultdict(list))
    points: dict[int, list[np.ndarray]] = field(default_factory=lambda: defaultdict(list))
    texts: list[tuple[str, np.ndarray, float, float, str, str, int]] = field(default_factory=list)

    def extent(self) -> tuple[np.ndarray, np.ndarray]:
        """The lowest and highest corner (mm) of the lines, the points and the texts' insertion points."""
        points = np.vstack([*(line for group in self.lines.values() for line in group),
                            *(point[None] for group in self.points.values() for point in group),
                            *(text[1][None] for text in self.texts)])
        return points.min(axis=0), points.max(axis=0)


def pen_of(entity: DXFGraphic, document: Drawing, parent: Pen | None) -> Pen:
    """The pen of ``entity``, inside a block reference drawn with ``parent`` (None in the model space)."""
    layer = entity.dxf.layer
    if parent is not None and layer == "0":
        layer = parent.layer
    layer_entry = document.layers.get(layer)
    colour = entity.dxf.get("color", BYLAYER)
    if colour == BYLAYER:
        colour = layer_entry.dxf.color
    elif colour == BYBLOCK:
        colour = parent.colour if parent is not None else PAPER_WHITE
    linetype = entity.dxf.get("linetype", "BYLAYER").upper()
    if linetype == "BYLAYER":
        linetype = layer_entry.dxf.linetype.upper()
    elif linetype == "BYBLOCK":
        linetype = parent.linetype if parent is not None else "CONTINUOUS"
    return Pen(layer, colour, linetype)


def _arc_points(center, radius: float, start_deg: float, end_deg: float) -> np.ndarray:
    sweep = (end_deg - start_deg) % 360.0 or 360.0
    angles = np.radians(start_deg + np.linspace(0.0, sweep, max(2, int(np.ceil(sweep / ARC_STEP_DEG)) + 1)))
    return np.asarray(center, float)[:2] + radius * np.c_[np.cos(angles), np.sin(angles)]


def _readable(rotation: float, horizontal: str, vertical: str) -> tuple[float, str, str]:
    """A text turned by 180 deg about its box's centre when it would read downwards-left (rotation in (90, 270]
    deg), as drafting reads a dimension from below or from the right: rotation and alignment."""
    if 90.0 < rotation % 360.0 <= 270.0:
        return rotation % 360.0 - 180.0, MIRRORED[horizontal], MIRRORED[vertical]
    return rotation, horizontal, vertical


def collect(entities, document: Drawing, ink: Ink, parent: Pen | None = None) -> Ink:
    """Add ``entities`` (and the virtual entities of dimensions and block references) to ``ink``."""
    for entity in entities:
        pen = pen_of(entity, document, parent)
        if pen.layer.lower() == "defpoints":
            continue
        kind = entity.dxftype()
        key = (pen.colour, pen.linetype, 0.0)
        if kind in ("DIMENSION", "INSERT"):
            collect(entity.virtual_entities(), document, ink, pen)
        elif kind == "LINE":
            ink.lines[key].append(np.array([entity.dxf.start, entity.dxf.end])[:, :2])
        elif kind == "LWPOLYLINE":
            points = entity.lwpoints.values.reshape(-1, 5)[:, :2]
            points = np.vstack([points, points[:1]]) if entity.closed else points
            ink.lines[(pen.colour, pen.linetype, float(entity.dxf.const_width))].append(points)
        elif kind == "CIRCLE":
            ink.lines[key].append(_arc_points(entity.dxf.center, entity.dxf.radius, 0.0, 360.0))
        elif kind == "ARC":
            ink.lines[key].append(_arc_points(entity.dxf.center, entity.dxf.radius, entity.dxf.start_angle,
                                              entity.dxf.end_angle))
        elif kind == "POINT":
            ink.points[pen.colour].append(np.asarray(entity.dxf.location)[:2])
        elif kind == "TEXT":
            ink.texts.append((entity.plain_text(), np.asarray(entity.dxf.insert)[:2], entity.dxf.height,
                              entity.dxf.get("rotation", 0.0), TEXT_ALIGNMENT[entity.dxf.get("halign", 0)],
                              "baseline", pen.colour))
        elif kind == "MTEXT":
            ink.texts.append((entity.plain_text(), np.asarray(entity.dxf.insert)[:2], entity.dxf.char_height,
                              *_readable(entity.get_rotation(), *ATTACHMENT[entity.dxf.get("attachment_point", 1)]),
                              pen.colour))
        else:
            raise ValueError(f"a sheet's {kind} entity is not drawn in the PDF")
    return ink


def _rgb(colour: int) -> tuple[float, float, float]:
    if colour == PAPER_WHITE:
        return (0.0, 0.0, 0.0)
    red, green, blue = aci2rgb(colour)
    return (red / 255, green / 255, blue / 255)


def draw_sheet(document: Drawing, figure: Figure, box: tuple[float, float, float, float]) -> None:
    """The model space of ``document`` to scale, centred in ``box`` (left, bottom, width, height as fractions of
    the figure), drawn on the figure itself (no axes: a page needs no ticks)."""
    ink = collect(document.modelspace(), document, Ink())
    low, high = ink.extent()
    box_inches = np.array(box[2:]) * figure.get_size_inches()
    inches_per_mm = float(np.min(box_inches / (high - low)))
    centre = (np.array(box[:2]) * figure.get_size_inches() + box_inches / 2) / inches_per_mm
    to_page = Affine2D().translate(*(centre - (low + high) / 2)).scale(inches_per_mm) + figure.dpi_scale_trans
    points_per_mm = 72 * inches_per_mm
    for (colour, linetype, width), lines in sorted(ink.lines.items()):
        figure.add_artist(LineCollection(lines, colors=[_rgb(colour)], linestyles=DASHES.get(linetype, "solid"),
                                         linewidths=width * points_per_mm or LINE_WIDTH, capstyle="butt",
                                         transform=to_page))
    for colour, points in sorted(ink.points.items()):
        figure.add_artist(Line2D(*np.array(points).T, linestyle="none", marker=".", markersize=2 * LINE_WIDTH,
                                 color=_rgb(colour), transform=to_page))
    for text, at, height, rotation, horizontal, vertical, colour in ink.texts:
        figure.text(at[0], at[1], text, fontsize=height * points_per_mm / CAP_HEIGHT_EM, rotation=rotation,
                    rotation_mode="anchor", ha=horizontal, va=vertical, color=_rgb(colour), parse_math=False,
                    transform=to_page, fontproperties=FONT)

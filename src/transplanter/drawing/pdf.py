"""Every DXF sheet of a run in one PDF, a page each (A4 landscape), for a quick look without CAD: ezdxf's
drawing add-on on matplotlib."""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import ezdxf
from ezdxf.addons.drawing import Frontend, RenderContext
from ezdxf.addons.drawing.config import BackgroundPolicy, Configuration
from ezdxf.addons.drawing.matplotlib import MatplotlibBackend
from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure

#: A4 landscape (inches).
PAGE_INCHES = (11.69, 8.27)


def write_pdf(sheets: Sequence[Path], path: Path) -> Path:
    """The DXF files ``sheets``, one a page with its file name on top, in ``path``; no creation date, so the same
    sheets give the same bytes."""
    config = Configuration(background_policy=BackgroundPolicy.WHITE)
    with PdfPages(path, metadata={"CreationDate": None}) as pages:
        for sheet in sheets:
            document = ezdxf.readfile(sheet)
            figure = Figure(figsize=PAGE_INCHES)
            axes = figure.add_axes((0.02, 0.02, 0.96, 0.92))
            Frontend(RenderContext(document), MatplotlibBackend(axes), config=config).draw_layout(
                document.modelspace())
            axes.set_aspect("equal")
            axes.set_axis_off()
            figure.suptitle(f"{sheet.name} (millimetres)")
            pages.savefig(figure)
    return path

"""Every DXF sheet of a run in one PDF, a page each (A4 landscape) with its file name on top, for a quick look
without CAD: the sheets drawn by ``sheet_page`` on matplotlib, the texts as text in a PDF core font (a reader
finds and copies them; nothing to embed)."""
from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import matplotlib
from ezdxf.document import Drawing
from matplotlib.backends.backend_pdf import PdfPages
from matplotlib.figure import Figure

from transplanter.drawing.sheet_page import FONT, draw_sheet

#: A4 landscape (inches).
PAGE_INCHES = (11.69, 8.27)


def write_pdf(sheets: Sequence[tuple[str, Drawing]], path: Path) -> Path:
    """The DXF documents of ``sheets`` (file name, document), one a page with its file name on top, in ``path``;
    no creation date, so the same sheets give the same bytes."""
    with matplotlib.rc_context({"pdf.use14corefonts": True}), \
            PdfPages(path, metadata={"CreationDate": None}) as pages:
        for name, document in sheets:
            figure = Figure(figsize=PAGE_INCHES)
            draw_sheet(document, figure, (0.02, 0.02, 0.96, 0.92))
            figure.suptitle(f"{name} (millimetres)", fontproperties=FONT, fontsize="x-large")
            pages.savefig(figure)
    return path

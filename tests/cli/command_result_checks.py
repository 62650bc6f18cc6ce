"""What the command runner reads of a result, checked in the form the protocol promises (``CommandResult``)."""
import json
from pathlib import Path

from matplotlib.figure import Figure

from transplanter.command_result import CommandResult
from transplanter.output_folder import report_json


def check_protocol(result, folder: Path):
    """Verdict, source, JSON, Markdown, screen text, figures and files of ``result``, each as promised."""
    assert isinstance(result, CommandResult)
    assert isinstance(result.source, str) and result.source
    assert result.passed == (not result.failures) and all(isinstance(f, str) and f for f in result.failures)
    assert result.produced or not result.passed
    report = result.to_json()
    assert json.loads(report_json(report))["source"] == report["source"]
    assert result.to_markdown().startswith("# ") and not result.to_text().startswith("# ")
    figures = result.draw_figures()
    assert all(isinstance(stem, str) and isinstance(figure, Figure) for stem, figure in figures.items())
    written = result.write_files(folder, animation=False)
    assert all(path.parent == folder and path.is_file() for path in written)

"""What every result a command reports gives: its verdict, its report, its figures and its files.

The seven design jobs and the two evaluations of a given design (``fivebar.evaluate_design``,
``parallelogram.evaluate_design``) return a ``CommandResult``. ``transplanter <command>`` reads
nothing else of them: it saves the figures and files, writes report.md and report.json, and sets
the exit code from ``passed`` and ``produced`` (0 passed, 1 failed a check, 2 no mechanism made).
A notebook calls the same methods.
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from transplanter.api_arguments import require_file_switches
from transplanter.figure_conventions import FigureDrawer, drawn

if TYPE_CHECKING:
    from matplotlib.figure import Figure


class CommandResult(ABC):
    """A mechanism's result as a command reports it (the report and drawing modules render it)."""

    @property
    @abstractmethod
    def source(self) -> str:
        """The file the report is about: the problem file, or the design file an evaluation judges."""

    @property
    @abstractmethod
    def failures(self) -> Sequence[str]:
        """Each check the result fails, in words with its numbers; empty when it passes."""

    @property
    def passed(self) -> bool:
        """Whether the result passes every check."""
        return not self.failures

    @property
    def produced(self) -> bool:
        """Whether the job made its mechanism. False only for a result that has a report but no mechanism
        (a reverse path that fails the monotonicity criterion gets no train); ``failures`` then says why."""
        return True

    @abstractmethod
    def to_json(self) -> dict[str, Any]:
        """The report as plain JSON types (mm, degrees): the content of report.json."""

    @abstractmethod
    def to_markdown(self, files: Sequence[str] = ()) -> str:
        """The report as Markdown (report.md); ``files`` names the files written beside it (figures, drawings,
        tables, animation), which the report may show or list."""

    def to_text(self) -> str:
        """The report on a terminal: the Markdown without files, its title a plain line."""
        return self.to_markdown().removeprefix("# ")

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        """The report's figures by file stem, each drawn when its drawer is called (the command line shares them
        out between two processes); none unless the result draws some."""
        return {}

    def draw_figures(self) -> dict[str, Figure]:
        """The report's figures (matplotlib) by file stem."""
        return drawn(self.figure_drawers())

    def write_files(self, folder: str | Path, animation: bool = True, solids: bool = True) -> list[Path]:
        """Write the files beyond the report and the figures into ``folder`` (drawings, tables, the STEP solids
        unless ``solids`` is False, and the animation unless ``animation`` is False); the paths written, none
        unless the result has such files. ProblemError when ``animation`` or ``solids`` is not True or False."""
        require_file_switches(animation, solids)
        return self._write_files(Path(folder), animation, solids)

    def _write_files(self, folder: Path, animation: bool, solids: bool) -> list[Path]:
        """The command's own files for ``write_files``: none unless the result has such files."""
        return []

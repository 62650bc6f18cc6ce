"""A command's output folder, written whole or not at all.

Files go to a hidden temporary folder beside the target; only when the run succeeds is it moved
into place, replacing an earlier output. A run that fails leaves no half folder and the earlier
output untouched. The target is checked before the work starts: it must be new, empty, or an
earlier output (a folder whose report.json lists every file in it), so ``--out .`` cannot wipe
a folder of other files.
"""
from __future__ import annotations

import contextlib
import json
import shutil
import tempfile
from pathlib import Path

from transplanter.errors import ProblemError

#: Kind of file by suffix, as report.json lists them under "files".
KINDS = {".json": "report", ".md": "report", ".png": "figure", ".dxf": "drawing", ".svg": "drawing",
         ".csv": "table", ".gif": "animation", ".mp4": "animation"}
#: Prefix of every file name of a run whose result failed a check.
FAILED_PREFIX = "FAILED-"


def files_by_kind(names) -> dict[str, list[str]]:
    """File names grouped by kind (``KINDS``; "other" for the rest), sorted."""
    grouped: dict[str, list[str]] = {}
    for name in sorted(names):
        grouped.setdefault(KINDS.get(Path(name).suffix, "other"), []).append(name)
    return grouped


def _earlier_output(folder: Path) -> bool:
    present = {path.name for path in folder.iterdir()}
    for report in ("report.json", FAILED_PREFIX + "report.json"):
        if report in present:
            try:
                listed = json.loads((folder / report).read_text()).get("files", {})
            except (ValueError, OSError, AttributeError):
                return False
            return isinstance(listed, dict) and present <= {name for names in listed.values() for name in names}
    return False


def check_target(out: str | Path):
    """Refuse (ProblemError) an ``--out`` that is a file or a folder holding files of something else."""
    target = Path(out)
    if target.exists() and not target.is_dir():
        raise ProblemError(f"--out = {out}: a file is there; expected a folder to write the results into")
    if target.is_dir() and any(target.iterdir()) and not _earlier_output(target):
        raise ProblemError(f"--out = {out}: the folder holds files that are not an earlier output of this command "
                           f"(its report.json does not list them); expected a new or empty folder, or an earlier output")


@contextlib.contextmanager
def staged(out: str | Path | None):
    """Yield a temporary folder beside ``out`` (None when ``out`` is None) and move it into place on success."""
    if out is None:
        yield None
        return
    check_target(out)
    target = Path(out).absolute()
    target.parent.mkdir(parents=True, exist_ok=True)
    work = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".partial", dir=target.parent))
    stage = work / target.name
    stage.mkdir()                       # made as any folder is (mkdtemp's own is private to the user)
    try:
        yield stage
    except BaseException:
        shutil.rmtree(work, ignore_errors=True)
        raise
    earlier = work / "earlier"
    if target.exists():
        target.replace(earlier)
    try:
        stage.replace(target)
    except OSError:
        if earlier.exists():
            earlier.replace(target)
        raise
    shutil.rmtree(work, ignore_errors=True)

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
import math
import os
import shutil
import tempfile
from pathlib import Path

from transplanter.errors import ProblemError
from transplanter.folder_swap import put_in_place
from transplanter.toml_fields import shown_name

#: Kind of file by suffix, as report.json lists them under "files".
KINDS = {".json": "report", ".md": "report", ".png": "figure", ".dxf": "drawing", ".svg": "drawing",
         ".csv": "table", ".gif": "animation", ".mp4": "animation", ".toml": "design", ".pdf": "drawing",
         ".step": "solid"}
#: Prefix of every file name of a run whose result failed a check.
FAILED_PREFIX = "FAILED-"


def report_json(report: dict, indent: int | None = 2) -> str:
    """``report`` as JSON text that any reader takes: a float that is not finite (NaN, Infinity,
    which JSON has no words for) is written as null."""
    def plain(value):
        if isinstance(value, float) and not math.isfinite(value):
            return None
        if isinstance(value, dict):
            return {key: plain(item) for key, item in value.items()}
        if isinstance(value, (list, tuple)):
            return [plain(item) for item in value]
        return value
    return json.dumps(plain(report), indent=indent, allow_nan=False)


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
    try:
        target.lstat()
    except FileNotFoundError:
        return
    except OSError as error:            # a name too long, a part of it that is a file, a folder not to be entered
        raise ProblemError(f"--out = {shown_name(out)}: {error.strerror}; expected a folder this user can create and "
                           "write into, each part of its name at most 255 bytes") from None
    if target.exists() and not target.is_dir():
        raise ProblemError(f"--out = {out}: a file is there; expected a folder to write the results into")
    if target.is_dir() and any(target.iterdir()) and not _earlier_output(target):
        raise ProblemError(f"--out = {out}: the folder holds files that are not an earlier output of this command "
                           "(its report.json does not list them); expected a new or empty folder, "
                           "or an earlier output")


def check_file(path: str | Path, option: str, suffixes: set[str], out: str | Path | None = None) -> Path:
    """Refuse (ProblemError) an output file that is a folder, has a suffix outside ``suffixes``, lies where
    nothing can be written or inside the ``--out`` folder ``out`` (replaced whole); the absolute path otherwise."""
    target = Path(path).absolute()
    if out is not None and target.resolve().is_relative_to(Path(out).resolve()):
        raise ProblemError(f"{option} = {path}: inside --out {out}, which is replaced whole when the run succeeds; "
                           "expected a file outside it")
    if target.suffix.lower() not in suffixes:
        raise ProblemError(f"{option} = {path}: expected a file name ending in one of {', '.join(sorted(suffixes))}")
    if target.is_dir():
        raise ProblemError(f"{option} = {path}: a folder is there; expected a file name")
    if not target.parent.is_dir() or not os.access(target.parent, os.W_OK | os.X_OK):
        raise ProblemError(f"{option} = {path}: {target.parent} is not a folder this user can write into")
    return target


def writable_folder(folder) -> Path:
    """``folder``, a folder a library function writes into, made if missing; ProblemError naming it when it is
    not a name, names a file, or cannot be made."""
    if not isinstance(folder, (str, os.PathLike)) or not str(folder):
        raise ProblemError(f"folder = {folder!r}: expected the name of a folder to write into (str or Path)")
    path = Path(folder)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise ProblemError(f"folder = {folder}: a file is there; expected a folder to write into") from None
    except OSError as error:
        raise ProblemError(f"folder = {folder}: cannot be made ({error.strerror}); expected a folder this user can "
                           "write into") from None
    return path


@contextlib.contextmanager
def staged_file(path: Path):
    """Yield a temporary name beside ``path`` and move it onto ``path`` only when the block succeeds."""
    partial = path.with_name(f".{path.stem}.{os.getpid()}.partial{path.suffix}")   # the suffix names the format
    try:
        yield partial
        os.replace(partial, path)
    finally:
        partial.unlink(missing_ok=True)


def _work_folder(out: str | Path, target: Path) -> Path:
    """The hidden temporary folder beside ``target``, or ProblemError naming ``--out`` when none can be made."""
    try:
        target.parent.mkdir(parents=True, exist_ok=True)
        return Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".partial", dir=target.parent))
    except OSError as error:
        raise ProblemError(f"--out = {out}: cannot write there ({error.strerror}): expected a folder this user "
                           "can create and write into") from None


@contextlib.contextmanager
def staged(out: str | Path | None):
    """Yield a temporary folder beside ``out`` (None when ``out`` is None) and put it in place of ``out`` in one
    step when the block succeeds (``folder_swap.put_in_place``)."""
    if out is None:
        yield None
        return
    check_target(out)
    target = Path(out).resolve() if Path(out).is_symlink() else Path(out).absolute()   # a link keeps pointing there
    work = _work_folder(out, target)
    try:
        stage = work / target.name
        stage.mkdir()                   # made as any folder is (mkdtemp's own is private to the user)
        yield stage
        try:
            put_in_place(stage, target, work / "earlier")
        except OSError as error:
            raise ProblemError(f"--out = {out}: cannot put the results there ({error.strerror}): expected a folder "
                               "this user can replace; it is left as it was") from None
    finally:
        shutil.rmtree(work, ignore_errors=True)

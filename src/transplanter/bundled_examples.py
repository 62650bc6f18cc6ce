"""The example problem files shipped in the package (``transplanter/examples``, the source checkout's
``examples/``), and ``transplanter examples DIR``, which copies them to DIR for a user to run and edit."""
from __future__ import annotations

from importlib.resources import files
from importlib.resources.abc import Traversable
from pathlib import Path

from transplanter.errors import ProblemError

#: What the examples folder ships: problem and design files, and the script that builds the reverse paths.
SUFFIXES = (".toml", ".py")


def _walk(folder: Traversable, prefix: Path = Path()) -> list[tuple[Path, Traversable]]:
    """Every example file under ``folder`` as (path relative to it, resource), in name order."""
    found = []
    for entry in sorted(folder.iterdir(), key=lambda entry: entry.name):
        if entry.is_dir() and entry.name != "__pycache__":
            found += _walk(entry, prefix / entry.name)
        elif entry.is_file() and entry.name.endswith(SUFFIXES):
            found.append((prefix / entry.name, entry))
    return found


def bundled_examples() -> list[tuple[Path, Traversable]]:
    """The shipped example files as (relative path, resource)."""
    return _walk(files("transplanter") / "examples")


def copy_examples(target: str | Path) -> list[Path]:
    """Copy every shipped example into ``target`` (made if missing); the files written.

    Raises
    ------
    ProblemError
        When ``target`` is a file, or already holds a file of the same name (an edited copy is never
        overwritten).
    """
    target = Path(target)
    if target.exists() and not target.is_dir():
        raise ProblemError(f"DIR = {target}: a file is there; expected a folder to copy the examples into")
    examples = bundled_examples()
    present = [str(relative) for relative, _ in examples if (target / relative).exists()]
    if present:
        raise ProblemError(f"DIR = {target}: already holds {present[0]}"
                           + (f" and {len(present) - 1} other examples" if len(present) > 1 else "")
                           + "; expected a new or empty folder (examples are never overwritten)")
    written = []
    for relative, resource in examples:
        path = target / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_bytes(resource.read_bytes())
        written.append(path)
    return written

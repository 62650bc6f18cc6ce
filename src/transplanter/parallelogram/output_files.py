"""Every file a designed onion transplanter gives besides its report and figures: the CSV tables, the gear
pair's drawings and STEP solids (with the extra transplanter[cad]) when its teeth are cut, and one driver turn
animated."""
from __future__ import annotations

from pathlib import Path

from transplanter import progress
from transplanter.api_arguments import require_file_switches, require_result
from transplanter.gears.drawings import write_drawings
from transplanter.gears.solid_files import write_solids
from transplanter.parallelogram.animation import write_animation
from transplanter.parallelogram.design_toml import write_design
from transplanter.parallelogram.result import ParallelogramResult
from transplanter.parallelogram.tables import write_tables


def write_files(result: ParallelogramResult, folder: str | Path, animation: bool = True, solids: bool = True
                ) -> list[Path]:
    """pareto.csv and trajectory.csv, the gears' CSV, SVG, DXF and STEP (with teeth; STEP unless ``solids`` is
    False), design.toml (``design_toml``) and, unless ``animation`` is False, animation.gif, in ``folder`` (made if
    missing); the files written."""
    require_file_switches(animation, solids)
    require_result(result, ParallelogramResult, "parallelogram")
    with progress.step("tables"):
        written = write_tables(result, folder)
    written.append(write_design(result, folder))
    if result.gear.teeth is not None:
        with progress.step("drawings"):
            written += write_drawings(result.gear, folder)
        if solids:
            with progress.step("solids"):
                written += write_solids(result.gear, Path(folder), result.problem.solid_sizes)
    if animation:
        with progress.step("animation"):
            written.append(write_animation(result, folder))
    return written

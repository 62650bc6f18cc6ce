"""Every file a designed five-bar gives besides its report and figures: the drawings and tables for the
workshop (``drawings.write_drawings``), STEP solids with the extra transplanter[cad] (``solid_files``) and one
turn animated with the cut teeth (``animation``)."""
from __future__ import annotations

from pathlib import Path

from transplanter import progress
from transplanter.api_arguments import require_file_switches, require_result
from transplanter.fivebar.animation import write_animation
from transplanter.fivebar.design_toml import write_design
from transplanter.fivebar.drawings import write_drawings
from transplanter.fivebar.gears_on_carrier import teeth_on_carrier
from transplanter.fivebar.result import FiveBarResult
from transplanter.fivebar.solid_files import write_solids


def write_files(result: FiveBarResult, folder: str | Path, animation: bool = True, solids: bool = True
                ) -> list[Path]:
    """The assembly (linkage.dxf), part and gear sheets, drawings.pdf, parts.csv, the CSV tables, the support cam's
    files, design.toml (``design_toml``), STEP solids with the extra transplanter[cad] unless ``solids`` is False
    and, unless ``animation`` is False, animation.gif (and .mp4 where ffmpeg exists) with the teeth turning on the
    carrier, in ``folder`` (made if missing); the files written."""
    require_file_switches(animation, solids)
    require_result(result, FiveBarResult, "fivebar")
    with progress.step("drawings"):
        written = write_drawings(result, folder)
    written.append(write_design(result, folder))
    if solids:
        with progress.step("solids"):
            written += write_solids(result, Path(folder))
    if animation:
        with progress.step("animation"):
            teeth = teeth_on_carrier(result.toothed, float(result.design.mech.carrier_length))
            written += write_animation(result, folder, teeth)
    return written

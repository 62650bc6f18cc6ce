"""The cam disc as a STEP solid (``solids.part_files``): ``cam.step``, the drawing's profile less its bore
(``cam.drawings``), extruded to the problem's ``cam.thickness_mm`` (default the plate rule of ``solids.sizes`` on the
bore's diameter), when the optional extra transplanter[cad] is installed."""
from __future__ import annotations

from pathlib import Path

from transplanter.cam.drawings import bore_radius
from transplanter.cam.result import CamResult
from transplanter.geometry.outline_thinning import thinned
from transplanter.solids.part_files import solids_note as part_solids_note
from transplanter.solids.part_files import write_part_solids
from transplanter.solids.step import BoredDisc

#: The disc's profile is thinned within this fraction of the base radius (its 3,600 samples took 342 s to make
#: and write under load).
DRAWN_WITHIN_BASE_RADII = 1e-5


def disc_outline(result: CamResult):
    """The profile (N, 2) mm thinned within ``DRAWN_WITHIN_BASE_RADII`` of the base radius."""
    return thinned(result.geometry.profile, DRAWN_WITHIN_BASE_RADII * result.base_radius)


def disc_thickness(result: CamResult) -> float:
    """The disc's thickness (mm): the problem's, else the plate rule on the bore's diameter."""
    return result.problem.solid_sizes.thickness(2 * bore_radius(result))


def solids_note(result: CamResult) -> str:
    """One line for the report: the disc's thickness, or why there is no solid."""
    return part_solids_note(None, disc_thickness(result), "cam disc")


def write_solids(result: CamResult, folder: Path) -> list[Path]:
    """``cam.step`` in ``folder``; none without the extra."""
    disc = BoredDisc("cam", disc_outline(result), bore_radius(result))
    return write_part_solids(folder, discs=[disc], thickness=disc_thickness(result))

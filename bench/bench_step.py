"""Time the STEP solids of smooth curves against the former solids of the outline's polyline, written and read back.

    python bench/bench_step.py [--every-baseline]

In this process: the main job (examples/vegetable_planting.toml, no tolerance analysis) is synthesised once, then
per gear of its train (57-77 teeth, shaper cut) and for the cam disc of examples/cam_flat_faced.toml:

- the package: ``solids.step.gear_solid`` / ``disc_solid`` (the cut outline, or the cam's thinned profile, as
  B-spline runs split at its corners), written by ``write_step``;
- the baseline, the former writer: the drawn outline (a gear's thinned within ``DRAWN_WITHIN_MODULES`` of the
  module, as the drawings have it) as a polyline face, the same bore cut, extruded and written by ``write_step``.

Printed per part: the time to make and write the solid, the file's size, its faces and the time OpenCASCADE's
STEP reader takes to read the file and to transfer it to a shape (what any CAD program on OpenCASCADE does on
opening it), with the ratios baseline / package. A baseline gear takes about a minute to transfer, so only the
first gear's is read back unless ``--every-baseline`` is given. Target: a gear read back in under a second.
"""
from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import build123d as bd
import numpy as np
from OCP.STEPControl import STEPControl_Reader

from transplanter import cam, fivebar
from transplanter.cam.drawings import bore_radius
from transplanter.cam.solid_files import disc_outline
from transplanter.fivebar.drawings import gear_drawings
from transplanter.fivebar.gears_on_carrier import cut_outlines, tooth_outlines
from transplanter.solids.step import BoredDisc, _keyed_hole, disc_solid, gear_solid, write_step

ROOT = Path(__file__).resolve().parents[1]
FACE_WIDTH = 15.0


def polyline_face(outline: np.ndarray):
    """The former face: one edge per segment of the outline."""
    return bd.make_face(bd.Polyline(*map(tuple, np.asarray(outline, float).tolist()), close=True))


def written(make, path: Path) -> tuple[float, object]:
    """Seconds to make the solid and write it to ``path``, and the solid."""
    start = time.perf_counter()
    solid = make()
    write_step(solid, path)
    return time.perf_counter() - start, solid


def read_back(path: Path) -> tuple[float, float]:
    """Seconds of STEPControl_Reader's ReadFile and of its TransferRoots."""
    reader = STEPControl_Reader()
    start = time.perf_counter()
    reader.ReadFile(str(path))
    read = time.perf_counter() - start
    reader.TransferRoots()
    return read, time.perf_counter() - start - read


def compare(name: str, package, baseline, folder: Path, read_baseline: bool) -> None:
    """Both sides of one part, printed in one line each and their ratios."""
    rows = {}
    for side, make in (("package", package), ("baseline", baseline)):
        path = folder / f"{name}_{side}.step"
        seconds, solid = written(make, path)
        read = read_back(path) if side == "package" or read_baseline else (float("nan"), float("nan"))
        rows[side] = (seconds, path.stat().st_size / 1e6, len(solid.faces()), *read)
        print(f"  {name:20s} {side:8s} write {seconds:6.2f} s  {rows[side][1]:6.2f} MB  {rows[side][2]:5d} faces  "
              f"read {read[0]:6.2f} s  transfer {read[1]:7.2f} s")
    ours, theirs = rows["package"], rows["baseline"]
    print(f"  {name:20s} baseline/package: write {theirs[0] / ours[0]:.2f}x  size {theirs[1] / ours[1]:.2f}x  "
          f"faces {theirs[2] / ours[2]:.1f}x  transfer {theirs[4] / ours[4]:.1f}x")


def main(every_baseline: bool) -> None:
    result = fivebar.synthesize(fivebar.load_problem(ROOT / "examples/vegetable_planting.toml"), tolerance=False)
    module = result.toothed.module
    drawn = gear_drawings(result, tooth_outlines(result.toothed))
    cut = gear_drawings(result, cut_outlines(result.toothed))
    cam_result = cam.synthesize(cam.load_problem(ROOT / "examples/cam_flat_faced.toml"))
    disc = BoredDisc("cam", disc_outline(cam_result), bore_radius(cam_result))
    with tempfile.TemporaryDirectory() as folder:
        print(f"main job's gears (module {module:g}, {FACE_WIDTH:g} mm wide):")
        for index, (ours, former) in enumerate(zip(cut, drawn, strict=True)):
            compare(ours.name, lambda gear=ours: gear_solid(gear, FACE_WIDTH, module),
                    lambda gear=former: bd.extrude(polyline_face(gear.outline) - _keyed_hole(gear.bore),
                                                   amount=FACE_WIDTH),
                    Path(folder), every_baseline or index == 0)
        print("cam disc (examples/cam_flat_faced.toml, 9 mm thick):")
        compare("cam", lambda: disc_solid(disc, 9.0),
                lambda: bd.extrude(polyline_face(disc.outline) - bd.Circle(disc.bore_radius), amount=9.0),
                Path(folder), True)


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--every-baseline", action="store_true",
                        help="read every baseline gear back (about a minute each), not only the first")
    main(parser.parse_args().every_baseline)

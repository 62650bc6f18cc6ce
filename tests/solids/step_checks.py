"""A STEP solid read back and checked against the outline it was made from: volume = area x height within 0.1 %,
the outline's bounding box and the height, the holes through its top face.

The test command installs the optional extra transplanter[cad], so a STEP test fails without build123d; it skips
only where ``WITHOUT_CAD`` = 1 in the environment says the extra is absent on purpose."""
import importlib
import os
from pathlib import Path

import numpy as np
import pytest

from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.solids.step import cad_installed, write_step

#: Set to 1 to skip the STEP tests in an environment without the optional extra transplanter[cad].
WITHOUT_CAD = "TRANSPLANTER_WITHOUT_CAD"

if not cad_installed() and os.environ.get(WITHOUT_CAD) == "1":
    pytest.skip(f"{WITHOUT_CAD}=1: no transplanter[cad]", allow_module_level=True)


def kernel():
    """build123d; a failed test where it is missing and ``WITHOUT_CAD`` does not say so."""
    if not cad_installed():
        pytest.fail(f"build123d is missing: install .[dev,cad] as the test command does, or set {WITHOUT_CAD}=1 "
                    "to skip the STEP tests", pytrace=False)
    return importlib.import_module("build123d")


def read_step(path: Path):
    """The solid of a STEP file."""
    return kernel().import_step(str(path))


def read_back(solid, path: Path):
    write_step(solid, path)
    return read_step(path)


def check_solid(solid, outline: np.ndarray, area: float, height: float, holes: int):
    """Volume = area x height within 0.1 %, the outline's bounding box and ``height``, ``holes`` through the top."""
    assert solid.volume == pytest.approx(area * height, rel=1e-3)
    box = solid.bounding_box()
    assert np.allclose([box.min.X, box.min.Y, box.max.X, box.max.Y], [*outline.min(axis=0), *outline.max(axis=0)],
                       atol=1e-6)
    assert abs(box.size.Z - height) < 1e-9
    assert len(solid.faces().sort_by(kernel().Axis.Z)[-1].inner_wires()) == holes


def keyed_hole_area(bore: KeyedBore) -> float:
    """The disk, less its segment beyond the keyway's chord, plus the keyway's rectangle from that chord out."""
    r, alpha = bore.radius, bore.half_angle
    return (np.pi * r**2 - r**2 * (alpha - np.sin(alpha) * np.cos(alpha))
            + bore.key.width * (bore.reach - r * np.cos(alpha)))

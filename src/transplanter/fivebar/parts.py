"""The five-bar's link plates as parts to make: the carrier (shafts O, S and A in the bent layout), rod AF, the push
plate E-F-P and the receiving plate BE, each in its own frame (first hole at the origin, second on +x), holes the
size of the shafts and hinge pins of ``fivebar.shafts``; the lengths dimensioned are the design's (report.json
``design``: carrier_length_OA, rod_length_AF, plate_link_length_EF, push_plate_EP and _FP,
receiving_plate_length_BE; ``gear_train.center_distances_mm`` for O-S and S-A)."""
from __future__ import annotations

import numpy as np

from transplanter.drawing.plate_sheet import Hole, PlatePart
from transplanter.drawing.sheet import TitleBlock
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.shafts import ShaftDesign
from transplanter.trains.toothed_train import ToothedTrain


def _on_x(length: float | np.ndarray) -> np.ndarray:
    return np.array([float(length), 0.0])


def link_parts(mech: FiveBar, toothed: ToothedTrain, shafts: ShaftDesign, title: str) -> list[PlatePart]:
    """Carrier, rod AF, push plate and receiving plate (module docstring)."""
    diameter = {name: shaft.diameter for name, shaft in shafts.shafts.items()}
    pin = diameter["hinge"]
    carrier_length = float(mech.carrier_length)
    e, f = np.asarray(mech.e_local, float), np.asarray(mech.f_local, float)
    # the plate in its own frame: E at the origin, F on +x, P where the plate's E and F put it
    along = (f - e) / np.linalg.norm(f - e)
    p_local = np.array([[along[0], along[1]], [-along[1], along[0]]]) @ (-e)
    carrier = PlatePart("carrier", (
        Hole("O", np.zeros(2), diameter["sun"]), Hole("A", _on_x(carrier_length), diameter["planet"]),
        Hole("S", np.asarray(toothed.shaft, float), diameter["intermediate"])),
        (("O", "A"), ("O", "S"), ("S", "A")), TitleBlock("carrier", 1, title))
    rod = PlatePart("rod_AF", (Hole("A", np.zeros(2), diameter["planet"]), Hole("F", _on_x(mech.rod_length), pin)),
                    (("A", "F"),), TitleBlock("rod AF", 1, title))
    plate = PlatePart("push_plate_EFP", (
        Hole("E", np.zeros(2), pin), Hole("F", _on_x(mech.link_length), pin), Hole("P", p_local, 0.0, pin / 2)),
        (("E", "F"), ("E", "P"), ("F", "P")), TitleBlock("push plate E-F-P", 1, title))
    receiving = PlatePart("receiving_plate_BE", (
        Hole("B", np.zeros(2), pin), Hole("E", _on_x(mech.receiving_length), pin)),
        (("B", "E"),), TitleBlock("receiving plate BE", 1, title))
    return [carrier, rod, plate, receiving]

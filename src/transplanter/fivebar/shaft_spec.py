"""The optional ``[shafts]`` table of a five-bar problem: shaft and hinge-pin diameters (mm).

Schema (docs/fivebar.md):

    [shafts]
    sun_mm = 30.0            # the frame's fixed shaft at O, keyed to the sun
    intermediate_mm = 20.0   # the carrier's intermediate shaft, keyed to both intermediate gears
    planet_mm = 20.0         # the shaft at A, keyed to the planet and to rod AF
    hinge_mm = 8.0           # the pins at B, E and F

Each is optional: a shaft not given is sized from the peak torque of the loads, a hinge pin not given from the
peak force at B, E and F (``shafts.sizing``). Keyed shafts take a parallel key of DIN 6885-1, so they lie over
6 and up to 130 mm.
"""
from __future__ import annotations

from dataclasses import dataclass

from transplanter.shafts.keys import DIN_6885
from transplanter.toml_fields import FieldReader

KEYED = ("sun", "intermediate", "planet")
NAMES = (*KEYED, "hinge")


@dataclass(frozen=True)
class ShaftSpec:
    """Given diameters by name of ``NAMES`` (mm); a name left out is sized by the default rules."""

    diameters_mm: dict[str, float]


def parse_shafts(read: FieldReader, table) -> ShaftSpec:
    """Validate ``[shafts]``: each diameter within DIN 6885-1 for a keyed shaft, positive and at most the
    table's largest for a hinge pin."""
    read.keys(table, {f"{name}_mm" for name in NAMES}, "shafts")
    low, high = DIN_6885[0][0][0], DIN_6885[-1][0][1]
    diameters = {}
    for name in NAMES:
        key = f"{name}_mm"
        if key in table:
            value = read.number(table, key, "shafts")
            floor = low if name in KEYED else 0
            if not floor < value <= high:
                read.fail(f"shafts.{key}", value, f"a diameter over {floor} and up to {high} mm"
                          + (" (a shaft with a DIN 6885-1 parallel key)" if name in KEYED else ""))
            diameters[name] = value
    return ShaftSpec(diameters)

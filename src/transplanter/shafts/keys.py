"""Parallel keys and keyways to DIN 6885-1 (form A): the key section and both groove depths by shaft diameter."""
from __future__ import annotations

from dataclasses import dataclass

from transplanter.errors import ProblemError


@dataclass(frozen=True)
class ParallelKey:
    """Key width b and height h, keyseat depth t1 in the shaft and keyway depth t2 in the hub (mm)."""

    width: float
    height: float
    shaft_depth: float
    hub_depth: float


#: (shaft diameter over, up to and including, in mm) -> key b x h, t1, t2 (DIN 6885-1).
DIN_6885 = (
    ((6, 8), ParallelKey(2, 2, 1.2, 1.0)),
    ((8, 10), ParallelKey(3, 3, 1.8, 1.4)),
    ((10, 12), ParallelKey(4, 4, 2.5, 1.8)),
    ((12, 17), ParallelKey(5, 5, 3.0, 2.3)),
    ((17, 22), ParallelKey(6, 6, 3.5, 2.8)),
    ((22, 30), ParallelKey(8, 7, 4.0, 3.3)),
    ((30, 38), ParallelKey(10, 8, 5.0, 3.3)),
    ((38, 44), ParallelKey(12, 8, 5.0, 3.3)),
    ((44, 50), ParallelKey(14, 9, 5.5, 3.8)),
    ((50, 58), ParallelKey(16, 10, 6.0, 4.3)),
    ((58, 65), ParallelKey(18, 11, 7.0, 4.4)),
    ((65, 75), ParallelKey(20, 12, 7.5, 4.9)),
    ((75, 85), ParallelKey(22, 14, 9.0, 5.4)),
    ((85, 95), ParallelKey(25, 14, 9.0, 5.4)),
    ((95, 110), ParallelKey(28, 16, 10.0, 6.4)),
    ((110, 130), ParallelKey(32, 18, 11.0, 7.4)),
)
#: Standard shaft diameters (mm) the default rules round to, within the table's range.
STANDARD_DIAMETERS = (8, 10, 12, 14, 15, 16, 17, 18, 20, 22, 25, 28, 30, 32, 35, 40, 45, 50, 55, 60, 65, 70, 75,
                      80, 85, 90, 95, 100, 110, 120, 130)


def parallel_key(diameter: float, field: str = "shafts") -> ParallelKey:
    """The DIN 6885-1 key of a shaft of ``diameter`` mm; ProblemError naming ``field`` outside the table."""
    for (over, up_to), key in DIN_6885:
        if over < diameter <= up_to:
            return key
    low, high = DIN_6885[0][0][0], DIN_6885[-1][0][1]
    raise ProblemError(f"{field}: {diameter:g} mm has no parallel key in DIN 6885-1; expected a shaft diameter over "
                       f"{low} and up to {high} mm")

"""The problem-file names of a toothed train's gearing fields, as its error messages name them: the five-bar's
``[gears]`` table by default, the reverse problem's ``[train]`` table in ``REVERSE_FIELDS``."""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class GearingFields:
    """Where the module and each centre distance are given, how both distances are named together, and what
    asks for a straight or a bent carrier."""

    module: str = "gears.module"
    center_distances: tuple[str, str] = ("gears.first_center_distance", "gears.second_center_distance")
    both_distances: str = "gears center distances"
    straight: str = 'gears.layout = "straight"'
    bent: str = 'gears.layout = "bent"'


#: The reverse problem gives both centre distances in one list, and the list sets the layout: a straight carrier
#: when they add up to the carrier length, else a bent one.
REVERSE_FIELDS = GearingFields("train.module", ("train.center_distances[0]", "train.center_distances[1]"),
                               "train.center_distances", "train.center_distances adding up to the carrier length",
                               "train.center_distances that bend the carrier")

"""The optional ``[load]`` table of a five-bar problem: the planting load at P and the links' masses for the
kinetostatics (``fivebar.kinetostatics``).

Schema (docs/fivebar.md), newtons and kilograms:

    [load]
    resisting_n = 20.0    # N against P's velocity over the pushing stroke (>= 0; the default, 20 N, without force_n)
    force_n = [0.0, 30.0] # or: a constant force at P over the pushing stroke (N, x and y); not with resisting_n
    masses_kg = { carrier = 1.5, rod = 0.6, plate = 0.2, receiving_plate = 0.3 }   # optional, each >= 0 (default 0)

The pushing stroke runs from the first to the last key pose's carrier turn; the weights act over the whole turn,
at the midpoints of OA (carrier), AF (rod with the planet gear) and BE (receiving plate) and at the centroid of the
plate's E, F, P.
"""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from transplanter.toml_fields import MAGNITUDE_LIMIT, ClassFields, FieldReader, is_finite_number, is_sequence

#: The links that may carry a mass, as ``masses_kg`` names them.
LINKS = ("carrier", "rod", "plate", "receiving_plate")
#: Planting resistance against P's velocity over the pushing stroke when the problem gives none (N).
DEFAULT_RESISTING_N = 20.0
#: Gravity (m/s^2), along -y.
GRAVITY = 9.81
_KEYS = {"resisting_n", "force_n", "masses_kg"}


def _bounded(value) -> bool:
    return is_finite_number(value) and abs(value) <= MAGNITUDE_LIMIT


@dataclass(frozen=True)
class LoadSpec:
    """The ``[load]`` table, validated.

    Attributes
    ----------
    force_n : ndarray (2,) or None
        A constant force at P over the pushing stroke (N); None: ``resisting_n`` against P's velocity.
    resisting_n : float or None
        Magnitude of the force against P's velocity over the pushing stroke (N, >= 0); ``DEFAULT_RESISTING_N``
        when neither is given, None with ``force_n``.
    masses_kg : dict
        Mass of each of ``LINKS`` (kg, >= 0; a link not named weighs nothing).
    """

    force_n: np.ndarray | None = None
    resisting_n: float | None = None
    masses_kg: dict = field(default_factory=dict)

    def __post_init__(self):
        check = ClassFields(self)
        if self.force_n is not None:
            if self.resisting_n is not None:
                check.fail("resisting_n", self.resisting_n, "None when force_n is given (one load or the other)")
            check.array("force_n", (2,))
        else:
            if self.resisting_n is None:
                object.__setattr__(self, "resisting_n", DEFAULT_RESISTING_N)
            check.number("resisting_n", 0.0, MAGNITUDE_LIMIT, "a finite force >= 0 (N)")
        masses = self.masses_kg
        if (not isinstance(masses, dict) or not set(masses) <= set(LINKS)
                or not all(_bounded(m) and m >= 0 for m in masses.values())):
            check.fail("masses_kg", masses, f"a dict of masses >= 0 (kg) named from {', '.join(LINKS)}")
        object.__setattr__(self, "masses_kg", {link: float(masses.get(link, 0.0)) for link in LINKS})


def parse_load(read: FieldReader, table) -> LoadSpec:
    """Validate ``[load]``.

    Raises
    ------
    ProblemError
        One line naming the field, the value and what would work.
    """
    read.keys(table, _KEYS, "load")
    if "force_n" in table and "resisting_n" in table:
        read.fail("load", {key: table[key] for key in ("force_n", "resisting_n")},
                  "force_n (a constant force at P) or resisting_n (a force against P's velocity), not both")
    force = table.get("force_n")
    if force is not None and not (is_sequence(force) and len(force) == 2 and all(_bounded(v) for v in force)):
        read.fail("load.force_n", force, f"[fx, fy]: two finite numbers (N) within ±{MAGNITUDE_LIMIT:.0e}")
    resisting = table.get("resisting_n")
    if resisting is not None and not (_bounded(resisting) and resisting >= 0):
        read.fail("load.resisting_n", resisting, f"a finite force from 0 to {MAGNITUDE_LIMIT:.0e} N")
    masses = table.get("masses_kg", {})
    read.keys(masses, set(LINKS), "load.masses_kg")
    for link, mass in masses.items():
        if not (_bounded(mass) and mass >= 0):
            read.fail(f"load.masses_kg.{link}", mass, f"a finite mass from 0 to {MAGNITUDE_LIMIT:.0e} kg")
    return LoadSpec(None if force is None else np.array(force, float),
                    None if resisting is None else float(resisting), dict(masses))

"""Toleranced dimensions and the ``[tolerances]`` table that sets them.

A dimension is a named, manufactured quantity of the built mechanism (a link length, a hinge's play, a
gear's assembly phase) with its nominal value and a symmetric limit ``tolerance`` (nominal +- tolerance),
in the unit the files use (mm or deg). The limit is read as the spread of a distribution:

- ``uniform`` (default): any value within the limits equally likely, standard deviation t / sqrt(3);
- ``normal``: the limits are three standard deviations, sigma = t / 3.

The tolerance allocation keeps each dimension within ``ALLOCATION_RANGE`` times its default tolerance.
"""
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field, replace

import numpy as np

from transplanter.errors import ProblemError
from transplanter.tolerance.iso286 import FIT, radial_play_mm
from transplanter.toml_fields import is_finite_number, shown

DISTRIBUTIONS = {"uniform": 1 / np.sqrt(3), "normal": 1 / 3}
#: Loosest and tightest tolerance the allocation may give, as factors of the dimension's default tolerance.
ALLOCATION_RANGE = (0.1, 10.0)
#: Monte Carlo samples and seed unless ``[tolerances]`` says otherwise.
SAMPLES, SEED = 10_000, 20261127
#: The samples' states are kept for the bands and conditions: 1,000,000 samples of the rice hoe's reverse train
#: peaked at 13.5 GB; at 50,000 the whole run peaks at 0.77 GB (reverse) and 0.98 GB (the five-bar example).
SAMPLES_RANGE = (100, 50_000)
#: Accuracy the seedlings need at the key poses unless ``[tolerances]`` says otherwise: P within 1 mm and the
#: plate within 1 deg (3 sigma), the order of a seedling's stem in a hole.
POSE_POSITION_MM, POSE_ANGLE_DEG = 1.0, 1.0
#: Radial play of a hinge (mm) whose shaft diameter is not set (no fit to take it from).
HINGE_PLAY_MM = 0.02
SETTING_KEYS = ("distribution", "samples", "seed", "pose_position_mm", "pose_angle_deg")


@dataclass(frozen=True)
class Dimension:
    """A manufactured dimension: ``nominal`` +- ``tolerance`` in ``unit`` ("mm" or "deg")."""

    name: str
    nominal: float
    tolerance: float
    unit: str
    what: str = ""


@dataclass(frozen=True)
class ToleranceSettings:
    """What a ``[tolerances]`` table sets: tolerances by dimension name (in the dimension's unit), the
    distribution, the Monte Carlo samples and seed, and the accuracy the key poses need (3 sigma)."""

    tolerances: Mapping[str, float] = field(default_factory=dict)
    distribution: str = "uniform"
    samples: int = SAMPLES
    seed: int = SEED
    pose_position_mm: float = POSE_POSITION_MM
    pose_angle_deg: float = POSE_ANGLE_DEG

    @property
    def sigma_per_tolerance(self) -> float:
        return float(DISTRIBUTIONS[self.distribution])

    def applied(self, dimensions: tuple[Dimension, ...], source: str = "tolerances") -> tuple[Dimension, ...]:
        """``dimensions`` with the tolerances set here; an unknown name is refused."""
        known = [d.name for d in dimensions]
        for name, value in self.tolerances.items():
            if name not in known:
                raise ProblemError(f"{source}: tolerances.{name}: unknown dimension; expected one of "
                                   f"{', '.join(known)}")
            if not (is_finite_number(value) and value >= 0):
                raise ProblemError(f"{source}: tolerances.{name} = {shown(value)!r}: expected a finite tolerance "
                                   ">= 0 in the dimension's unit (mm or deg)")
        return tuple(replace(d, tolerance=float(self.tolerances.get(d.name, d.tolerance))) for d in dimensions)


def hinge_plays(diameters_mm: Mapping[str, float | None]) -> list[Dimension]:
    """``clearance_<hinge>_x`` / ``_y``: where each pin sits in its hole, within the radial play (mm) of an
    H7/g6 fit on the hinge's shaft diameter (``iso286``), or ``HINGE_PLAY_MM`` where none is set (None)."""
    plays = {hinge: (HINGE_PLAY_MM, "radial play, no shaft diameter set") if d is None
             else (radial_play_mm(d, f"shaft diameter of hinge {hinge}"), f"radial play, {FIT} on {d:g} mm")
             for hinge, d in diameters_mm.items()}
    return [Dimension(f"clearance_{h}_{axis}", 0.0, play, "mm", what)
            for h, (play, what) in plays.items() for axis in "xy"]


def parse_tolerances(table: Mapping, names: tuple[str, ...], source: str,
                     own_settings: tuple[str, ...] = ()) -> ToleranceSettings:
    """The ``[tolerances]`` table of a problem file: ``name = tolerance`` for any of ``names`` (the dimension's
    unit, >= 0), and the settings of ``SETTING_KEYS``; ``own_settings`` are the mechanism's own keys, which its
    problem reads. Each bad entry is refused naming the field."""
    def fail(key, value, expected):
        raise ProblemError(f"{source}: tolerances.{key} = {shown(value)!r}: expected {expected}")

    if not isinstance(table, Mapping):
        raise ProblemError(f"{source}: tolerances = {shown(table)!r}: expected a table [tolerances]")

    tolerances = {}
    for key, value in table.items():
        if key in SETTING_KEYS or key in own_settings:
            continue
        if key not in names:
            fail(key, value, f"a dimension name ({', '.join(names)}) or a setting "
                 f"({', '.join((*SETTING_KEYS, *own_settings))})")
        if not (is_finite_number(value) and value >= 0):
            fail(key, value, "a finite tolerance >= 0 in the dimension's unit (mm or deg)")
        tolerances[key] = float(value)
    distribution = table.get("distribution", "uniform")
    if distribution not in DISTRIBUTIONS:
        fail("distribution", distribution, " or ".join(f'"{d}"' for d in DISTRIBUTIONS))
    samples = table.get("samples", SAMPLES)
    if isinstance(samples, bool) or not isinstance(samples, int) or not SAMPLES_RANGE[0] <= samples <= SAMPLES_RANGE[1]:
        fail("samples", samples, f"a whole number of Monte Carlo samples from {SAMPLES_RANGE[0]} to {SAMPLES_RANGE[1]}")
    seed = table.get("seed", SEED)
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        fail("seed", seed, "a whole number >= 0")
    accuracy = {}
    for key, default in (("pose_position_mm", POSE_POSITION_MM), ("pose_angle_deg", POSE_ANGLE_DEG)):
        value = table.get(key, default)
        if not (is_finite_number(value) and value > 0):
            fail(key, value, "a finite accuracy > 0 (3 sigma at every key pose)")
        accuracy[key] = float(value)
    return ToleranceSettings(tolerances, distribution, samples, seed, **accuracy)

"""A built sun-idler-planet train (the rice-transplanter paper's three gears, ``reverse.idler_train``) in the
terms of ``planetary_gears``: its ``gear_rows`` over the carrier turns, so ``planetary_gears.planet_turn``
turns its planet as it does a four-gear train's.

The idler is both intermediate gears: it turns by psi(c), the sun rolled on it, and its far side (half a turn
round) drives the planet. With the sun's radius r(c) and the idler's far-side radius q(psi) at their contacts
(center distance a both), psi' = r / (a - r), psi'' = a r' / (a - r)^2 against c, and chi' = q / (a - q),
chi'' = a q' / (a - q)^2 against psi; the driven gears' radii at the contacts are a - r and a - q. chi(c) is
the train rolled from its pitch curves (``roll_idler_train``, the verification's own), so the nominal built
train is the verified one. Its gears' phases are the sun's and the planet's (``IDLER_GEARS``): the idler turns
alone on its shaft, so it has no phase against another gear there.
"""
from __future__ import annotations

import numpy as np

from transplanter.reverse.idler_train import IdlerTrain, roll_idler_train
from transplanter.trains.rolling import arc_map, conjugate_curve

IDLER_GEARS = ("sun", "planet")
IDLER_GEAR_DIMENSION_NAMES = ("backlash_stage_1", "backlash_stage_2", *(f"phase_{gear}" for gear in IDLER_GEARS))


def idler_gear_rows(train: IdlerTrain, c: np.ndarray) -> np.ndarray:
    """``planetary_gears.gear_rows`` of the idler train at carrier turns ``c`` (rad): (8, T)."""
    a, sun = train.center_distance, train.stage_one.driver
    idler = conjugate_curve(sun, a)
    chi = roll_idler_train(train.stage_one, train.planet, np.r_[0.0, c])[0]
    psi = arc_map(idler).inverse(arc_map(sun)(c))
    r, r_slope, _ = sun.evaluate(c)
    q, q_slope, _ = idler.evaluate(psi + np.pi)
    return np.vstack([c, chi[1:] - chi[0], r / (a - r), a * r_slope / (a - r) ** 2, q / (a - q),
                      a * q_slope / (a - q) ** 2, a - r, a - q])

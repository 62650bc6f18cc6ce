"""The pressure angle of the planetary train's two meshes over the carrier turn, and its bound.

At a mesh's contact the two pitch curves share a tangent that leans by mu from the normal to the line
of centres: tan(mu) = r_theta / r of the stage's driver in its own polar angle (``train_pitch_tangent``,
derived in ``derivations/train_pitch_tangent.py`` from rho', rho'' and k; the driven curve gives -mu,
the same line). Teeth of nominal pressure angle alpha0 push along a line at alpha0 - mu from the gears'
motion at the contact on the drive flank (the driver pushes the driven gear on) and at alpha0 + mu on
the coast flank (the load drives back); whichever flank carries the load, the angle is at most
alpha0 + |mu|, the same from either gear. A circle pair (rho' constant) has mu = 0: alpha0 all round.

``Gearing.max_pressure_angle`` (``[gears] max_pressure_angle_deg``) bounds alpha0 + |mu|, i.e.
(tan(mu) / tan(limit - alpha0))^2 <= 1: ``pressure_rows`` gives that row in CasADi for the design NLP's
grid, ``pressure_excess`` the numpy measure of how far a fine grid breaks it, and ``StagePressureAngles``
the evaluation of a design over the turn (largest angle, where, which flank; the report's fields and the
message of a stage above the limit).
"""
from __future__ import annotations

from dataclasses import dataclass

import casadi as ca
import numpy as np

from transplanter._generated.train_pitch_tangent import train_pitch_tangent
from transplanter.generated import casadi_function, numpy_twin
from transplanter.trains.planetary import RelativeMotion
from transplanter.trains.toothed_train import Gearing

#: The two meshes, in the train's order.
STAGES = ("sun -> first intermediate", "second intermediate -> planet")
#: Rows of ``train_pitch_tangent`` (sun, first intermediate, second intermediate, planet) of each stage's driver.
DRIVER_ROWS = [0, 2]
FLANKS = ("drive", "coast")
#: A stage passes while its largest pressure angle exceeds the limit by at most this fraction of the allowance
#: max_pressure_angle - pressure_angle: IPOPT holds the rows on its grid to ~1e-8, the fine grid between them
#: to what the exchange reaches (it adds the turns where the excess is larger than this).
PRESSURE_GAP = 1e-3

_tangent = numpy_twin(train_pitch_tangent)


def stage_leans(relative: RelativeMotion, correction: float, turns: np.ndarray) -> np.ndarray:
    """mu (rad) of each stage's driver, shape (2, len(turns)), at carrier turns ``turns`` (rad), for the
    relative angle rho(c) and the train's correction k (eq 12)."""
    turns = np.asarray(turns, float)
    slope = [relative.evaluate(turns, order) for order in (1, 2)]
    return _tangent(slope, [np.full_like(turns, correction)])[1][DRIVER_ROWS]


def pressure_rows(derivatives, correction, gearing: Gearing) -> ca.SX:
    """(tan(mu) / tan(limit - alpha0))^2 - 1 of each stage, shape (2, points): <= 0 where the teeth's
    pressure angle alpha0 + |mu| stays within ``gearing.max_pressure_angle``.

    ``derivatives`` is (2, points) or more rows of rho', rho'' (the design NLP's grid: the first two rows of
    its rho', rho'', rho''' are used), ``correction`` the scalar k."""
    points = derivatives.shape[1]
    tangent = casadi_function(train_pitch_tangent).map(points)(derivatives[:2, :], ca.repmat(correction, 1, points))[0]
    allowance = np.tan(gearing.max_pressure_angle - gearing.pressure_angle)
    return (tangent[DRIVER_ROWS, :] / allowance) ** 2 - 1


def pressure_excess(leans: np.ndarray, gearing: Gearing) -> np.ndarray:
    """By how much alpha0 + |mu| exceeds the limit at each turn, as a fraction of the allowance
    limit - alpha0 (the largest over the stages; positive where it is broken), from ``stage_leans``."""
    allowance = gearing.max_pressure_angle - gearing.pressure_angle
    return (np.abs(leans).max(axis=0) - allowance) / allowance


@dataclass(frozen=True)
class StagePressureAngles:
    """The pressure angle of each mesh of ``STAGES`` over the carrier turn (radians).

    Attributes
    ----------
    turns : ndarray, shape (n,)
        Carrier turns (rad).
    leans : ndarray, shape (2, n)
        mu of each stage's driver (``stage_leans``).
    nominal, limit : float
        alpha0 (``Gearing.pressure_angle``) and ``Gearing.max_pressure_angle``.
    """

    turns: np.ndarray
    leans: np.ndarray
    nominal: float
    limit: float

    @property
    def flanks(self) -> np.ndarray:
        """Pressure angle (rad) on the drive and coast flank of each stage, alpha0 - mu and alpha0 + mu:
        shape (2 stages, 2 flanks of ``FLANKS``, n)."""
        return self.nominal + np.stack([-self.leans, self.leans], axis=1)

    def _worst(self) -> tuple[np.ndarray, np.ndarray]:
        """Per stage: the flank (0 drive, 1 coast) and the index of the turn of the largest pressure angle."""
        flat = self.flanks.reshape(2, -1).argmax(axis=1)
        return np.divmod(flat, len(self.turns))

    @property
    def largest(self) -> np.ndarray:
        """Largest pressure angle of each stage over the turn (rad): alpha0 + max |mu|."""
        return self.flanks.max(axis=(1, 2))

    @property
    def largest_turn(self) -> np.ndarray:
        """Carrier turn (rad) of each stage's largest pressure angle."""
        return self.turns[self._worst()[1]]

    @property
    def largest_flank(self) -> tuple[str, ...]:
        """Which flank of each stage carries its largest pressure angle: "drive" (mu < 0) or "coast" (mu > 0)."""
        return tuple(FLANKS[flank] for flank in self._worst()[0])

    @property
    def passed(self) -> bool:
        return not self.failures()

    def failures(self) -> list[str]:
        """One line per stage whose largest pressure angle is above the limit (beyond ``PRESSURE_GAP``)."""
        tolerance = PRESSURE_GAP * (self.limit - self.nominal)
        return [f"stage {stage}: largest pressure angle {np.degrees(angle):.2f} deg ({flank} flank) at carrier turn "
                f"{np.degrees(turn):.1f} deg, above gears.max_pressure_angle_deg = {np.degrees(self.limit):g}"
                for stage, angle, turn, flank in zip(STAGES, self.largest, self.largest_turn, self.largest_flank,
                                                     strict=True) if angle > self.limit + tolerance]

    def to_json(self) -> dict:
        """Report fields (degrees), lists in ``STAGES`` order: the largest pressure angle, the carrier turn and
        flank where it occurs, and the nominal angle and limit it lies between."""
        return {"gear_pressure_angle_stages": list(STAGES),
                "gear_pressure_angle_max_deg": np.degrees(self.largest).tolist(),
                "gear_pressure_angle_max_at_deg": np.degrees(self.largest_turn).tolist(),
                "gear_pressure_angle_max_flank": list(self.largest_flank),
                "gear_pressure_angle_nominal_deg": float(np.degrees(self.nominal)),
                "gear_pressure_angle_limit_deg": float(np.degrees(self.limit))}

    def summary(self) -> str:
        """One sentence for report.md."""
        stages = "; ".join(f"{stage} {np.degrees(angle):.2f} deg ({flank} flank) at carrier turn {np.degrees(turn):.1f}"
                           f" deg" for stage, angle, turn, flank in zip(STAGES, self.largest, self.largest_turn,
                                                                        self.largest_flank, strict=True))
        return (f"Largest gear pressure angle over the turn (nominal {np.degrees(self.nominal):g} deg plus the pitch "
                f"curves' lean, limit {np.degrees(self.limit):g} deg): {stages}.")


def stage_pressure_angles(relative: RelativeMotion, correction: float, gearing: Gearing,
                          turns: np.ndarray) -> StagePressureAngles:
    """The pressure angle of both meshes at carrier turns ``turns`` (rad) of the train that realises
    ``relative`` with correction k = ``correction`` (``PlanetaryTrain.correction``), cut as ``gearing`` says."""
    return StagePressureAngles(np.asarray(turns, float), stage_leans(relative, correction, turns),
                               gearing.pressure_angle, gearing.max_pressure_angle)

"""The support cam timed to the pushing mechanism (used by ``fivebar.support``, the five-bar's ``[support]`` table).

The cam turns with the carrier through a drive of ratio ``drive_ratio`` (cam turns per carrier turn;
the paper's chain drive, 1). The five-bar's stages, as carrier angles from the start of the push, give
the cam's segments: push -> rise (the plate from low to high), receive -> far dwell, return -> return,
rest -> near dwell (the paper's 110, 80, 85 and 85 deg).
"""
from __future__ import annotations

import numpy as np

from transplanter.cam.problem import LAWS, TURN_TOLERANCE_DEG
from transplanter.errors import ProblemError

STAGES = ("push", "receive", "return", "rest")
_KINDS = {"push": "rise", "receive": "dwell", "return": "return", "rest": "dwell"}


def timed_segments(stage_angles, drive_ratio: float, swing: float, law: str = "harmonic") -> list[dict]:
    """``[[segments]]`` rows of the support cam (the cam file's fields, degrees) from the five-bar's stages.

    Parameters
    ----------
    stage_angles : sequence of 4 floats
        Carrier angles (rad) of push, receive, return and rest, in that order from the start of the push.
    drive_ratio : float
        Cam turns per carrier turn; the cam's segments are the stages times this, and must make one cam turn.
    swing : float
        The follower's swing psi (rad, eq 15).
    law : str
        Motion law of the rise and the return.

    Raises
    ------
    ProblemError
        When the stages times the ratio are not one cam turn, or an input is out of range.
    """
    angles = np.asarray(stage_angles, float)
    if angles.shape != (4,) or not np.all(np.isfinite(angles)) or np.any(angles <= 0):
        raise ProblemError(f"stage_angles = {np.degrees(angles).tolist()} deg: expected four positive carrier angles "
                           f"({', '.join(STAGES)})")
    if not (np.isfinite(drive_ratio) and drive_ratio > 0):
        raise ProblemError(f"drive_ratio = {drive_ratio!r}: expected a positive number of cam turns per carrier turn")
    if law not in LAWS:
        raise ProblemError(f"law = {law!r}: expected one of {', '.join(LAWS)}")
    cam_angles = np.degrees(angles * drive_ratio)
    if abs(cam_angles.sum() - 360.0) > TURN_TOLERANCE_DEG:
        raise ProblemError(f"stage_angles x drive_ratio = {cam_angles.sum():.6g} deg of cam: expected one cam turn "
                           f"(360 deg); with these stages the ratio would be {2 * np.pi / angles.sum():.9g}")
    rows = []
    for stage, angle in zip(STAGES, cam_angles, strict=True):
        row = {"kind": _KINDS[stage], "angle_deg": float(angle)}
        if row["kind"] != "dwell":
            row.update(law=law, swing_deg=float(np.degrees(swing)))
        rows.append(row)
    return rows


def plate_clearance(plate_x: float, hinge_e_x) -> tuple[float, int]:
    """Clearance (mm) of the support plate's line x = x_Z left of the receiving plate's hinge E over a turn:
    min(x_E) - x_Z, and the sample where it is least. Negative: the plates collide."""
    x = np.asarray(hinge_e_x, float)
    k = int(np.argmin(x))
    return float(x[k] - plate_x), k

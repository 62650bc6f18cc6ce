"""Table 5 of Wang et al. 2025 (the seedling-support mechanism) evaluated as printed, and the nearest readings
that are consistent.

As printed: l_HZ = 116, l_GH = 30, l_CG = 200, l_CK = 58 mm, angle KCG = 30 deg, C = (65.40, -80.00),
D = (143.86, 42.03), psi = 36 deg, the plate at x_Z = -130 between heights 5 and 124 mm, a cam of base
radius 30 mm with a 6 mm roller (section 4). The questions: does the rocker-slider assemble at both
heights (eq 14), what swing does it give (eq 15), and can the cam centred at D drive the arm C-K?

Readings tried where the print does not close:
- ``plate_below_rod``: H = Z - (0, l_HZ) instead of Z + (0, l_HZ);
- ``heights_from_datum``: the heights 5 and 124 mm measured from a datum y0 (the furrow opener's floor,
  which the text names) instead of from y = 0; y0 solved so that the swing is Table 5's 36 deg;
- for the cam, whose centre D lies beyond the arm's reach: the arm C-K on either side of C-G or of its
  extension (a bell crank), and the cam centre moved along the line C-D to where the roller at the plate's
  low position sits on the base pitch circle (R_b + R_r = 36 mm); and the textbook layout with the arm
  square to the cam radius on the base circle. Each cam is analysed by the cam tool with the paper's
  program (110 deg rise, 80 dwell, 85 return, 85 dwell, harmonic), turning clockwise with the carrier.
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from transplanter.cam.kinematics import oscillating_start
from transplanter.cam.support_linkage import ASSEMBLIES, SupportLinkage, support_swing
from transplanter.geometry.planar import unit

PIVOT_C = np.array([65.40, -80.00])
CAM_CENTER_D = np.array([143.86, 42.03])
PLATE_LENGTH, ROD_LENGTH, ROCKER_LENGTH, ARM_LENGTH = 116.0, 30.0, 200.0, 58.0
ARM_ANGLE = np.radians(30.0)             # angle KCG
SWING = np.radians(36.0)
PLATE_X, LOW_HEIGHT, HIGH_HEIGHT = -130.0, 5.0, 124.0
BASE_RADIUS, ROLLER_RADIUS = 30.0, 6.0
PROGRAM = (("rise", 110.0), ("dwell", 80.0), ("return", 85.0), ("dwell", 85.0))


def printed_linkage(plate_below_rod: bool = False) -> SupportLinkage:
    return SupportLinkage(PIVOT_C.copy(), ROCKER_LENGTH, ROD_LENGTH, PLATE_LENGTH, PLATE_X, plate_below_rod)


def _degrees(values):
    return [None if not np.isfinite(v) else float(np.degrees(v)) for v in np.atleast_1d(values)]


def _swing_json(linkage: SupportLinkage, low: float, high: float) -> dict:
    swing = support_swing(linkage, low, high)
    return {"theta_cg_deg": {"low": _degrees(swing.low_angle), "high": _degrees(swing.high_angle)},
            "swing_deg": _degrees(swing.swing), "closure_residual_mm": None if not np.isfinite(swing.residual_mm)
            else swing.residual_mm, "assembles": bool(np.isfinite(swing.swing).any())}


def datum_for_swing(assembly: int, swing: float = SWING) -> float | None:
    """The datum y0 (mm) that makes the swing ``swing`` (rad) with heights y0 + 5 and y0 + 124, for the
    assembly with index ``assembly``; None when no datum in the closing range gives it."""
    linkage = printed_linkage()
    _, high = linkage.reach()
    # |C - H| within the reach at both heights bounds y0 (H's x is fixed).
    dx = PLATE_X - PIVOT_C[0]
    span = np.sqrt(high**2 - dx**2)
    lowest = PIVOT_C[1] - span - (LOW_HEIGHT + PLATE_LENGTH)
    highest = PIVOT_C[1] + span - (HIGH_HEIGHT + PLATE_LENGTH)
    grid = np.linspace(lowest, highest, 401)[1:-1]

    def excess(y0):
        return support_swing(linkage, y0 + LOW_HEIGHT, y0 + HIGH_HEIGHT).swing[assembly] - swing

    values = np.array([excess(y) for y in grid])
    crossings = np.flatnonzero(np.isfinite(values[:-1]) & np.isfinite(values[1:])
                               & (np.sign(values[:-1]) != np.sign(values[1:])))
    if not crossings.size:
        return None
    k = crossings[np.argmin(np.abs(grid[crossings]))]          # the datum nearest y = 0
    from scipy.optimize import brentq  # here: every five-bar run imports this module, few reach this line

    return float(brentq(excess, grid[k], grid[k + 1], xtol=1e-12))


DIRECTION_CD = (CAM_CENTER_D - PIVOT_C) / np.linalg.norm(CAM_CENTER_D - PIVOT_C)


def _cam_center_on_line(roller_center: np.ndarray) -> float | None:
    """Distance t > 0 along C -> D at which the cam centre C + t u is the base pitch radius from the roller
    centre (the root nearest D), or None."""
    offset = roller_center - PIVOT_C
    along = DIRECTION_CD @ offset
    disc = along**2 - offset @ offset + (BASE_RADIUS + ROLLER_RADIUS) ** 2
    roots = along + np.array([-1.0, 1.0]) * np.sqrt(max(disc, 0.0))
    roots = roots[roots > 0] if disc >= 0 else roots[:0]
    return float(roots.max()) if roots.size else None


def _cam_problem(pivot_from_cam: np.ndarray, pulled: bool, swing: float):
    from transplanter.cam.problem import parse_problem

    segments = []
    for kind, angle in PROGRAM:
        row = {"kind": kind, "angle_deg": angle}
        if kind != "dwell":
            row.update(law="harmonic", swing_deg=float(np.degrees(swing)))
        segments.append(row)
    return parse_problem({"title": "Table 5 cam, nearest consistent reading",
                          "cam": {"base_radius": BASE_RADIUS, "direction": "clockwise"},
                          "follower": {"kind": "oscillating", "roller_radius": ROLLER_RADIUS,
                                       "pivot": pivot_from_cam.tolist(), "arm_length": ARM_LENGTH,
                                       "roller_side": "pulled" if pulled else "pushed"},
                          "segments": segments}, "Table 5")


def _cam_verdict(problem) -> dict:
    from transplanter.cam.synthesis import synthesize

    result = synthesize(problem)
    report = result.to_json()
    return {"roller_side": report["follower"]["roller_side"], "pivot_from_cam_mm": report["follower"]["pivot_mm"],
            "max_pressure_angle_deg": report["max_pressure_angle_deg"],
            "min_curvature_radius_mm": report["min_curvature_radius_mm"], "undercut": report["undercut"],
            "passed": result.passed, "failures": result.failures}


def _side_of(pivot_from_cam: np.ndarray, roller_from_cam: np.ndarray, swing: float) -> bool:
    """True when the roller at ``roller_from_cam`` is where the cam tool puts a pulled roller."""
    problem = _cam_problem(pivot_from_cam, True, swing)
    start, _ = oscillating_start(problem.follower, BASE_RADIUS + ROLLER_RADIUS, problem.direction)
    return bool(np.linalg.norm(pivot_from_cam + ARM_LENGTH * unit(start) - roller_from_cam) < 1e-6 * ARM_LENGTH)


def cam_readings(low_angle: float, high_angle: float, swing: float) -> list[dict]:
    """For each place of the arm C-K, angle KCG = 30 deg on either side of C-G, or of its extension beyond C (a
    bell crank): the roller K at the plate's low and high positions, its distance from D, the angle between C-K
    and C-D, and the cam centre on the line C-D (beyond C) that puts K on the base pitch circle at the low
    position, with the cam tool's verdict on that cam when the rise moves K outward (a cam can only push)."""
    out = []
    for beyond in (False, True):
        for side in (1, -1):
            turn = (np.pi if beyond else 0.0) + side * ARM_ANGLE
            k_low, k_high = (PIVOT_C + ARM_LENGTH * unit(a + turn) for a in (low_angle, high_angle))
            reading = {"arm": ("opposite" if beyond else "beside") + " C-G", "kcg_side": side,
                       "k_low": k_low.tolist(), "k_high": k_high.tolist(),
                       "distance_d_to_k_low_mm": float(np.linalg.norm(k_low - CAM_CENTER_D)),
                       "angle_ck_to_cd_deg": float(np.degrees(np.arccos(np.clip(DIRECTION_CD @ unit(low_angle + turn),
                                                                                -1, 1))))}
            t = _cam_center_on_line(k_low)
            reading["cam_center_on_cd"] = None
            if t is not None:
                center = PIVOT_C + t * DIRECTION_CD
                outward = bool(np.linalg.norm(k_high - center) > BASE_RADIUS + ROLLER_RADIUS)
                reading["cam_center_on_cd"] = {"center": center.tolist(), "distance_c_to_cam_mm": t,
                                               "moved_from_d_mm": float(np.linalg.norm(center - CAM_CENTER_D)),
                                               "rise_moves_roller_outward": outward}
                if outward:
                    pivot = PIVOT_C - center
                    pulled = _side_of(pivot, k_low - center, abs(swing))
                    reading["cam_center_on_cd"]["cam"] = _cam_verdict(_cam_problem(pivot, pulled, abs(swing)))
            out.append(reading)
    return out


def perpendicular_layout(rise_sense: float, swing: float = SWING) -> dict:
    """The textbook layout nearest the table: the cam centre on the line C-D at sqrt(l_CK^2 + 36^2) from C, where
    the arm is square to the cam radius on the base circle; the cam tool's verdict for each roller side, and
    whether its rise turns the arm the way that lifts the plate (``rise_sense``: +1 counterclockwise, the
    rocker's turn from the plate's low to its high position)."""
    distance = float(np.hypot(ARM_LENGTH, BASE_RADIUS + ROLLER_RADIUS))
    pivot = -distance * DIRECTION_CD
    cams = []
    for pulled in (True, False):
        problem = _cam_problem(pivot, pulled, swing)
        _, sense = oscillating_start(problem.follower, BASE_RADIUS + ROLLER_RADIUS, problem.direction)
        cams.append({**_cam_verdict(problem), "rise_turns_arm": "counterclockwise" if sense > 0 else "clockwise",
                     "lifts_plate": bool(sense == rise_sense)})
    return {"distance_c_to_cam_mm": distance, "center": (PIVOT_C + distance * DIRECTION_CD).tolist(), "cams": cams}


@dataclass(frozen=True)
class Table5Evaluation:
    """What Table 5 gives, as printed and in the nearest consistent readings (plain JSON in ``report``)."""

    report: dict = field(default_factory=dict)

    def to_json(self) -> dict:
        return self.report


def evaluate_table5() -> Table5Evaluation:
    """Evaluate Table 5 of Wang et al. 2025 (see the module docstring): linkage as printed, readings, cam."""
    printed = printed_linkage()
    reach = printed.reach()
    distances = [float(np.linalg.norm(printed.slider_point(h) - PIVOT_C)) for h in (LOW_HEIGHT, HIGH_HEIGHT)]
    report: dict[str, Any] = {
        "printed": {"distance_c_to_h_mm": distances, "reach_mm": list(reach),
                    **_swing_json(printed, LOW_HEIGHT, HIGH_HEIGHT)},
        "plate_below_rod": _swing_json(printed_linkage(True), LOW_HEIGHT, HIGH_HEIGHT),
        "heights_from_datum": [],
        "cam_at_d": {"distance_c_to_d_mm": float(np.linalg.norm(CAM_CENTER_D - PIVOT_C)),
                     "roller_reach_mm": [ARM_LENGTH - BASE_RADIUS - ROLLER_RADIUS,
                                         ARM_LENGTH + BASE_RADIUS + ROLLER_RADIUS],
                     "nearest_roller_to_d_mm": float(np.linalg.norm(CAM_CENTER_D - PIVOT_C) - ARM_LENGTH),
                     "base_pitch_radius_mm": BASE_RADIUS + ROLLER_RADIUS},
    }
    report["cam_at_d"]["can_drive"] = bool(report["cam_at_d"]["nearest_roller_to_d_mm"] <= BASE_RADIUS + ROLLER_RADIUS)
    rise_senses = []
    for index, assembly in enumerate(ASSEMBLIES):
        datum = datum_for_swing(index)
        entry: dict[str, Any] = {"assembly": assembly, "datum_y0_mm": datum}
        if datum is not None:
            swing = support_swing(printed, datum + LOW_HEIGHT, datum + HIGH_HEIGHT)
            entry.update(theta_cg_deg={"low": _degrees(swing.low_angle[index])[0],
                                       "high": _degrees(swing.high_angle[index])[0]},
                         swing_deg=_degrees(swing.swing[index])[0], closure_residual_mm=swing.residual_mm,
                         cam_readings=cam_readings(swing.low_angle[index], swing.high_angle[index], swing.swing[index]))
            rise_senses.append(float(np.sign(swing.high_angle[index] - swing.low_angle[index])))
        report["heights_from_datum"].append(entry)
    if len(set(rise_senses)) != 1:
        raise AssertionError(f"the rocker lifts the plate turning both ways in the readings: {rise_senses}")
    report["perpendicular_layout"] = perpendicular_layout(rise_senses[0])
    return Table5Evaluation(report)

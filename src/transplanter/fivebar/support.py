"""The seedling support of Wang et al. 2025 (section 4: a cam and the rocker-slider of eq 14-15), designed with the
five-bar it serves.

The cam turns with the carrier (``drive_ratio`` cam turns per carrier turn, clockwise), its cam angle 0 at pose 1.
Its segments come from the designed motion's own stages (``design_stages``), or are typed; the cam is designed and
checked by the cam tool (``cam.synthesize``). The follower's swing turns the rocker C-G through eq (14) to the plate
height; the plate line x = x_Z is checked against the receiving plate's hinge E over the turn
(``cam.timing.plate_clearance``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.cam.kinematics import motion_at
from transplanter.cam.problem import parse_problem as parse_cam
from transplanter.cam.result import CamResult
from transplanter.cam.synthesis import synthesize as synthesize_cam
from transplanter.cam.table5 import Table5Evaluation, evaluate_table5
from transplanter.cam.timing import plate_clearance, timed_segments
from transplanter.errors import ProblemError
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.loop_closure import close_loop
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.fivebar.support_problem import CAM_DIRECTION, SupportSpec
from transplanter.geometry.planar import TWO_PI

#: Carrier turns at which the plate and hinge E are followed (0.1 deg apart).
TURN_SAMPLES = 3600


def design_stages(key_turns, return_turns) -> np.ndarray:
    """Carrier angles (rad) of push, receive, return and rest: the push from pose 1 to the last key pose, the
    receive from there to the first return point, the return to the last return point, the rest to the turn's end."""
    marks = np.r_[0.0, key_turns[-1], return_turns[0], return_turns[-1], TWO_PI]
    return np.diff(marks)


@dataclass(frozen=True)
class SupportDesign:
    """The support designed for a five-bar.

    Attributes
    ----------
    spec : SupportSpec
    stages : ndarray (4,)
        Carrier angles of push, receive, return and rest (rad) the cam's segments came from.
    typed : bool
        The segments were typed (``support.segments_deg``), not taken from the design's stages.
    cam : CamResult
        The cam, designed and checked by the cam tool.
    carrier_turns : ndarray (N,)
        Clockwise turns since pose 1 (rad).
    rocker_angle, plate_height : ndarray (N,)
        theta_CG (rad) and y_Z (mm) over the turn.
    hinge_e : ndarray (N, 2)
        The receiving plate's hinge E over the turn (mm).
    clearance_mm : float
        Smallest x_E - x_Z over the turn; ``clearance_turn`` (rad) is where.
    table5 : Table5Evaluation
        The published support (Wang et al. 2025 Table 5) evaluated, which the report sets beside this one.
    """

    spec: SupportSpec
    stages: np.ndarray
    typed: bool
    cam: CamResult
    carrier_turns: np.ndarray
    rocker_angle: np.ndarray
    plate_height: np.ndarray
    hinge_e: np.ndarray
    clearance_mm: float
    clearance_turn: float
    table5: Table5Evaluation

    @property
    def failures(self) -> list[str]:
        found = [f"support cam: {reason}" for reason in self.cam.failures]
        stuck = ~np.isfinite(self.plate_height)
        if stuck.any():
            found.append(f"support rod G-H cannot reach the plate line at {int(stuck.sum())} of {stuck.size} carrier "
                         f"turns, from {np.degrees(self.carrier_turns[stuck].min()):.1f} deg")
        if not self.clearance_mm >= 0:
            found.append(f"support plate at x_Z = {self.spec.linkage.plate_x:g} mm is {-self.clearance_mm:.3f} mm "
                         "right "
                         f"of the receiving plate's hinge E at carrier turn {np.degrees(self.clearance_turn):.1f} deg")
        return found

    @property
    def passed(self) -> bool:
        return not self.failures

    def cam_angle(self, carrier_turns) -> np.ndarray:
        return cam_angle(self.spec, carrier_turns)

    def joints(self, carrier_turns) -> dict[str, np.ndarray]:
        """C, G, H, Z, the roller centre K and the cam centre D (each (n, 2) mm) at carrier turns (rad)."""
        spec, linkage = self.spec, self.spec.linkage
        rocker = rocker_angles(spec, self.cam, self.cam_angle(carrier_turns))
        height = linkage.plate_height(rocker, _above(spec))
        n = rocker.size
        arm = rocker - spec.bell_crank
        return {"C": np.tile(linkage.pivot, (n, 1)), "G": linkage.joint_g(rocker),
                "H": linkage.slider_point(height), "Z": np.column_stack([np.full(n, linkage.plate_x), height]),
                "K": linkage.pivot + spec.follower.arm_length * np.column_stack([np.cos(arm), np.sin(arm)]),
                "D": np.tile(spec.cam_center, (n, 1))}

    def cam_outline(self, carrier_turn: float, curve: str = "profile") -> np.ndarray:
        """The cam's profile (or ``"pitch"`` curve) on the ground at a carrier turn (rad), (N, 2) mm."""
        angle = CAM_DIRECTION * float(self.cam_angle(carrier_turn))
        turn = np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])
        return self.spec.cam_center + getattr(self.cam.geometry, curve) @ turn.T


def cam_angle(spec: SupportSpec, carrier_turns) -> np.ndarray:
    """The cam's turn (rad, in its clockwise sense, from 0 at pose 1) at carrier turns (rad)."""
    return np.mod(spec.drive_ratio * np.asarray(carrier_turns, float), TWO_PI)


def _above(spec: SupportSpec) -> float:
    """+1 when H stands above G at the low plate (eq 14's slider side), else -1."""
    g = spec.linkage.joint_g(spec.low_angle)
    return 1.0 if spec.linkage.slider_point(spec.heights[0])[1] >= g[1] else -1.0


def rocker_angles(spec: SupportSpec, cam: CamResult, cam_angle) -> np.ndarray:
    """theta_CG (rad) at cam angles: the low rocker angle turned by the follower's swing towards the high one."""
    swing, _ = motion_at(cam.problem.segments, np.atleast_1d(cam_angle))
    return spec.low_angle - np.sign(spec.swing) * swing[0]


def support_cam(spec: SupportSpec, stages: np.ndarray, source: str) -> CamResult:
    """The support's cam from carrier stage angles (rad), designed and checked by the cam tool."""
    follower = spec.follower
    assert follower.pivot is not None, "the support's follower swings about its pivot C"
    try:
        rows = timed_segments(stages, spec.drive_ratio, abs(spec.swing), spec.law)
    except ProblemError as error:
        raise ProblemError(f"{source}: support.drive_ratio = {spec.drive_ratio!r}: {error}") from None
    return synthesize_cam(parse_cam({
        "title": "seedling support cam",
        "cam": {"base_radius": spec.base_radius, "direction": "clockwise"},
        "follower": {"kind": "oscillating", "roller_radius": follower.roller_radius, "pivot": follower.pivot.tolist(),
                     "arm_length": follower.arm_length, "roller_side": "pulled" if follower.pulled else "pushed"},
        "segments": rows, "limits": {"pressure_angle_deg": float(np.degrees(spec.pressure_limit))}}, source))


def design_support(spec: SupportSpec, mech: FiveBar, relative: RelativeAngle, key_turns, return_turns,
                   source: str) -> SupportDesign:
    """Time the support to a five-bar: the cam from the design's stages (or the typed angles), the plate over a turn,
    and the clearance of the plate line left of hinge E.

    Raises
    ------
    ProblemError
        The stages times the drive ratio are not one cam turn (the message gives the ratio that would be).
    """
    typed = spec.segments is not None
    stages = (np.asarray(spec.segments) / spec.drive_ratio if spec.segments is not None
              else np.asarray(design_stages(key_turns, return_turns), float))
    cam = support_cam(spec, stages, f"{source} [support]")
    turns = np.linspace(0.0, TWO_PI, TURN_SAMPLES, endpoint=False)
    hinge_e = close_loop(mech, turns, relative.evaluate(turns))["e"]
    clearance, k = plate_clearance(spec.linkage.plate_x, hinge_e[:, 0])
    rocker = rocker_angles(spec, cam, cam_angle(spec, turns))
    return SupportDesign(spec, stages, typed, cam, turns, rocker, spec.linkage.plate_height(rocker, _above(spec)),
                         hinge_e, clearance, float(turns[k]), evaluate_table5())

"""The optional ``[support]`` table of a five-bar problem: the seedling support of Wang et al. 2025 section 4
(a disc cam with an oscillating roller follower driving the rocker-slider C-G-H-Z of eq 14-15), designed with the
pushing mechanism. Everything that does not depend on the five-bar is checked here, before the synthesis.

Schema (docs/fivebar.md, "Seedling support"), mm and degrees:

    [support]
    plate_x = -200.0              # x_Z: the line the plate H-Z slides on, left of the receiving plate's hinge E
    heights = [-307.0, -188.0]    # y_Z at the plate's lowest and highest
    pivot = [-4.6, -80.0]         # C, the oscillating bar's pivot
    rocker_length = 200.0         # l_CG
    rod_length = 30.0             # l_GH
    plate_length = 116.0          # l_HZ
    plate_below_rod = false       # H = Z + (0, l_HZ) (eq 14 as printed); true: H = Z - (0, l_HZ)
    assembly = 1                  # which of eq 14's two rocker angles (1 or -1)
    cam_center = [35.96, -16.91]  # D; the cam turns with the carrier (clockwise)
    arm_length = 58.0             # l_CK, pivot to roller centre
    base_radius = 30.0            # mm
    roller_radius = 6.0           # mm
    roller_side = "pulled"        # or "pushed" (cam/problem.py): the side whose rise lifts the plate
    law = "harmonic"              # rise and return law
    pressure_angle_deg = 45.0     # the cam's limit
    drive_ratio = 1.0             # cam turns per carrier turn (the paper's chain: 1)
    segments_deg = [110, 80, 85, 85]  # optional cam angles of push, receive, return, rest; absent: the design's stages
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.cam.kinematics import oscillating_start
from transplanter.cam.problem import LAWS, TURN_TOLERANCE_DEG, Follower, check_base_radius
from transplanter.cam.support_linkage import ASSEMBLIES, SupportLinkage, support_swing
from transplanter.toml_fields import FieldReader

#: The cam turns as the carrier does: clockwise (a chain keeps the sense).
CAM_DIRECTION = -1
_KEYS = {"plate_x", "heights", "pivot", "rocker_length", "rod_length", "plate_length", "plate_below_rod", "assembly",
         "cam_center", "arm_length", "base_radius", "roller_radius", "roller_side", "law", "pressure_angle_deg",
         "drive_ratio", "segments_deg"}


@dataclass(frozen=True)
class SupportSpec:
    """The ``[support]`` table, validated (mm, radians).

    Attributes
    ----------
    linkage : SupportLinkage
        C, l_CG, l_GH, l_HZ and x_Z.
    heights : (float, float)
        y_Z at the plate's lowest and highest (mm).
    assembly : int
        Index into ``ASSEMBLIES`` of the rocker angle used.
    follower : Follower
        The cam's oscillating roller follower, its pivot C relative to the cam centre.
    cam_center : ndarray (2,)
        D (mm).
    base_radius : float
    law : str
    pressure_limit : float
        rad.
    drive_ratio : float
        Cam turns per carrier turn.
    segments : ndarray (4,) or None
        Typed cam angles of push, receive, return and rest (rad); None: from the design's stages.
    low_angle, high_angle : float
        theta_CG at the low and high plate (rad, eq 14); ``swing`` = low - high (eq 15).
    bell_crank : float
        Angle from the arm C-K to the rocker C-G (rad, counterclockwise), fixed so the roller sits on the base
        circle when the plate is low.
    """

    linkage: SupportLinkage
    heights: tuple[float, float]
    assembly: int
    follower: Follower
    cam_center: np.ndarray
    base_radius: float
    law: str
    pressure_limit: float
    drive_ratio: float
    segments: np.ndarray | None
    low_angle: float
    high_angle: float
    bell_crank: float

    @property
    def swing(self) -> float:
        """psi = theta_CG1 - theta_CG2 (rad, eq 15), signed."""
        return self.low_angle - self.high_angle


def _length(read: FieldReader, table: dict, key: str, default: float | None = None) -> float:
    if key not in table and default is not None:
        return default
    return read.length(table, key, "support")


def parse_support(read: FieldReader, table, hinge_e_range: tuple[float, float] | None) -> SupportSpec:
    """Validate ``[support]``; ``hinge_e_range`` is the problem's ``ranges.x_e`` (x of hinge E in pose 1, mm), if any:
    the plate line must lie left of it.

    Raises
    ------
    ProblemError
        One line naming the field, the value and what would work.
    """
    read.keys(table, _KEYS, "support")
    for key in ("plate_x", "heights", "pivot", "cam_center"):
        if key not in table:
            read.fail(f"support.{key}", None, "a value (see docs/fivebar.md, Seedling support)")
    plate_x = read.number(table, "plate_x", "support")
    if hinge_e_range is not None and not plate_x < hinge_e_range[0]:
        read.fail("support.plate_x", plate_x, f"a line left of the receiving plate's hinge E, which ranges.x_e puts "
                  f"from x = {hinge_e_range[0]:g} to {hinge_e_range[1]:g} mm in pose 1 (x_Z < {hinge_e_range[0]:g}; "
                  "the clearance over the whole turn is checked after the design)")
    heights = read.numbers(table, "heights", "support", 2)
    if len(heights) != 2 or not heights[0] < heights[1]:
        read.fail("support.heights", table["heights"], "[low, high] y of Z (mm), low < high")
    linkage = SupportLinkage(read.point(table["pivot"], "support.pivot"), _length(read, table, "rocker_length"),
                             _length(read, table, "rod_length"), _length(read, table, "plate_length"), plate_x,
                             read.flag(table, "plate_below_rod", "support", False))
    assembly = table.get("assembly", 1)
    if assembly not in ASSEMBLIES or isinstance(assembly, bool):
        read.fail("support.assembly", assembly, "1 or -1 (the two rocker angles of eq 14)")
    index = ASSEMBLIES.index(assembly)
    swing = support_swing(linkage, *heights)
    low, high = float(swing.low_angle[index]), float(swing.high_angle[index])
    if not (np.isfinite(low) and np.isfinite(high)):
        near, far = linkage.reach()
        distances = [float(np.linalg.norm(linkage.slider_point(h) - linkage.pivot)) for h in heights]
        read.fail("support.heights", heights.tolist(), f"heights at which C-G-H closes: |CH| = "
                  f"{distances[0]:.2f} and {distances[1]:.2f} mm, while l_CG and l_GH reach {near:g} to {far:g} mm")
    sides = [np.sign(linkage.slider_point(h)[1] - linkage.joint_g(a)[1])
             for a, h in ((low, heights[0]), (high, heights[1]))]
    if sides[0] != sides[1]:
        read.fail("support.assembly", assembly, f"an assembly in which H stays on one side of G between the heights "
                  f"(with this one the rod G-H passes horizontal, a dead point; try assembly = {-assembly})")
    rise_sense = np.sign(np.angle(np.exp(1j * (high - low))))
    side = table.get("roller_side", "pulled")
    if side not in ("pulled", "pushed"):
        read.fail("support.roller_side", side, '"pulled" or "pushed"')
    center = read.point(table["cam_center"], "support.cam_center")
    follower = Follower("oscillating", _length(read, table, "roller_radius", 6.0), pivot=linkage.pivot - center,
                        arm_length=_length(read, table, "arm_length", 58.0), pulled=side == "pulled")
    base = _length(read, table, "base_radius", 30.0)
    _check_cam_reach(read, follower, base)
    start, sense = oscillating_start(follower, base + follower.roller_radius, CAM_DIRECTION)
    if sense != rise_sense:
        other = "pushed" if side == "pulled" else "pulled"
        read.fail("support.roller_side", side, f'"{other}": with "{side}" the cam\'s rise turns the rocker '
                  f"{'counterclockwise' if sense > 0 else 'clockwise'}, which lowers the plate")
    law = table.get("law", "harmonic")
    if law not in LAWS:
        read.fail("support.law", law, "one of " + ", ".join(f'"{name}"' for name in LAWS))
    limit = read.number(table, "pressure_angle_deg", "support") if "pressure_angle_deg" in table else 45.0
    if not 0 < limit < 90:
        read.fail("support.pressure_angle_deg", limit, "an angle between 0 and 90 deg")
    ratio = read.number(table, "drive_ratio", "support") if "drive_ratio" in table else 1.0
    if not ratio > 0:
        read.fail("support.drive_ratio", ratio,
                  "a positive number of cam turns per carrier turn (1: the paper's chain)")
    segments = None
    if "segments_deg" in table:
        segments = read.numbers(table, "segments_deg", "support", 4)
        if len(segments) != 4 or np.any(segments <= 0) or abs(segments.sum() - 360.0) > TURN_TOLERANCE_DEG:
            read.fail("support.segments_deg", table["segments_deg"], "four positive cam angles (push, receive, return, "
                      f"rest) adding up to 360 deg (these add up to {float(np.sum(segments)):.6g})")
        segments = np.radians(segments)
    return SupportSpec(linkage, (float(heights[0]), float(heights[1])), index, follower, center, base, law,
                       float(np.radians(limit)), ratio, segments, low, high,
                       float(np.angle(np.exp(1j * (low - start)))))


def _check_cam_reach(read: FieldReader, follower: Follower, base: float):
    """``cam.problem.check_base_radius`` with the support's field names."""
    names = {"follower.roller_radius": "support.roller_radius", "follower.arm_length": "support.arm_length"}

    def fail(field, value, expected):
        read.fail(names.get(field, field), value, expected)

    check_base_radius(follower, base, fail)

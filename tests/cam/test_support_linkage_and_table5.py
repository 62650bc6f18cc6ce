"""The seedling-support rocker-slider (Wang et al. 2025, eq 14-15) and the evaluation of Table 5."""
from itertools import pairwise

import numpy as np
import pytest
from scipy.optimize import brentq

from transplanter._generated.cam_support import support_rocker_closure
from transplanter.cam import table5
from transplanter.cam.support_linkage import SupportLinkage, support_swing
from transplanter.generated import numpy_twin


def test_rocker_angle_recovers_a_constructed_linkage(rng):
    """Ground truth: a rocker at a known angle, a rod end H placed on the plate's line at the rod length from G;
    solving eq (14) for that plate height gives the angle back (one of the two assemblies), and the derived
    closure vanishes there."""
    for _ in range(20):
        pivot, rocker, rod = rng.normal(0, 50, 2), rng.uniform(100, 250), rng.uniform(20, 60)
        angle = rng.uniform(-np.pi, np.pi)
        g = pivot + rocker * np.array([np.cos(angle), np.sin(angle)])
        x = g[0] + rng.uniform(-0.9, 0.9) * rod
        h_y = g[1] + np.sqrt(rod**2 - (x - g[0]) ** 2)
        linkage = SupportLinkage(pivot, rocker, rod, 116.0, x)
        solved = linkage.rocker_angles(h_y - 116.0)
        assert np.abs(np.angle(np.exp(1j * (solved - angle)))).min() < 1e-9
        assert np.abs(linkage.closure_residual(h_y - 116.0, solved)).max() < 1e-9 * rocker
        (residual,) = numpy_twin(support_rocker_closure)([*pivot, rocker, rod], [x, h_y], [solved[0]])
        assert abs(residual[0]) < 1e-8 * rocker**2


def _independent_angles(h, pivot=table5.PIVOT_C):
    """Rocker angles closing C-G-H, by bracketing |G(theta) - H| - l_GH on a fine grid and brentq."""
    def gap(theta):
        g = pivot + table5.ROCKER_LENGTH * np.array([np.cos(theta), np.sin(theta)])
        return np.linalg.norm(g - h) - table5.ROD_LENGTH
    grid = np.linspace(-np.pi, np.pi, 3601)
    values = np.array([gap(t) for t in grid])
    return [brentq(gap, a, b, xtol=1e-14)
            for (a, b), (va, vb) in zip(pairwise(grid), pairwise(values), strict=True) if va * vb < 0]


@pytest.fixture(scope="module")
def report():
    return table5.evaluate_table5().to_json()


def test_table5_as_printed_does_not_assemble(report):
    """With H = Z + (0, l_HZ) (eq 14 as printed), |C - H| is 280.3 and 374.9 mm, beyond l_CG + l_GH = 230."""
    for height, distance in zip((5.0, 124.0), report["printed"]["distance_c_to_h_mm"], strict=True):
        h = np.array([-130.0, height + 116.0])
        assert distance == pytest.approx(np.hypot(*(h - table5.PIVOT_C)), rel=1e-12) and distance > 230.0
        assert not _independent_angles(h)
    assert report["printed"]["assembles"] is False and report["printed"]["reach_mm"] == [170.0, 230.0]


def test_plate_below_rod_swing(report):
    """With H = Z - (0, l_HZ) the chain closes; swings 31.94 and 34.58 deg, not Table 5's 36 (independent solve,
    each assembly the side of C-H that G is on)."""
    swings = report["plate_below_rod"]["swing_deg"]

    def by_side(height):
        h = np.array([-130.0, height - 116.0])
        side = {}
        for theta in _independent_angles(h):
            g = table5.PIVOT_C + 200.0 * np.array([np.cos(theta), np.sin(theta)])
            (dx, dy), (gx, gy) = h - table5.PIVOT_C, g - table5.PIVOT_C
            side[np.sign(dx * gy - dy * gx)] = theta
        return side
    low, high = by_side(5.0), by_side(124.0)
    independent = sorted(abs(np.degrees(np.angle(np.exp(1j * (low[k] - high[k]))))) for k in (1, -1))
    assert sorted(swings) == pytest.approx(independent, abs=1e-9)
    assert swings == pytest.approx([31.936150927649, 34.583038214579], abs=1e-9)


def test_heights_from_a_datum_give_36_deg(report):
    """Heights measured from a datum y0 (the furrow-opener floor): y0 = -312.34 mm (or -208.66 mm in the other
    assembly) gives the 36 deg swing; re-evaluated here from the datum alone."""
    datums = [entry["datum_y0_mm"] for entry in report["heights_from_datum"]]
    assert datums == pytest.approx([-312.3438791554, -208.6561208446], abs=1e-6)
    for index, datum in enumerate(datums):
        swing = support_swing(table5.printed_linkage(), datum + 5.0, datum + 124.0)
        assert np.degrees(swing.swing[index]) == pytest.approx(36.0, abs=1e-9)
        assert swing.residual_mm < 1e-9


def test_the_cam_at_d_cannot_reach_the_arm(report):
    """|CD| = 145.08 mm while the roller on the 58 mm arm can be at most 58 + 36 = 94 mm from C on the base pitch
    circle: no cam of base radius 30 and roller 6 centred at D touches it (the roller stays 87.08 mm from D)."""
    cam_at_d = report["cam_at_d"]
    assert cam_at_d["distance_c_to_d_mm"] == pytest.approx(np.hypot(143.86 - 65.40, 42.03 + 80.00), rel=1e-12)
    assert cam_at_d["nearest_roller_to_d_mm"] == pytest.approx(cam_at_d["distance_c_to_d_mm"] - 58.0, rel=1e-12)
    assert cam_at_d["can_drive"] is False
    for entry in report["heights_from_datum"]:
        for reading in entry["cam_readings"]:
            assert reading["distance_d_to_k_low_mm"] >= cam_at_d["nearest_roller_to_d_mm"] - 1e-9


def test_cam_moved_along_cd_and_the_square_layout(report):
    """Moved along C-D until the roller touches the base pitch circle, the cam sits where the arm nearly points at
    its centre (pressure angle far over 45 deg); the layout with the arm square to the base radius passes on the
    pushed side."""
    for entry in report["heights_from_datum"]:
        for reading in entry["cam_readings"]:
            moved = reading["cam_center_on_cd"]
            if moved is None:
                continue
            k_low, center = np.array(reading["k_low"]), np.array(moved["center"])
            assert np.linalg.norm(k_low - center) == pytest.approx(36.0, rel=1e-12)
            if "cam" in moved:
                assert max(moved["cam"]["max_pressure_angle_deg"][k] for k in ("rise", "return")) > 45.0
    pulled, pushed = report["perpendicular_layout"]["cams"]
    assert report["perpendicular_layout"]["distance_c_to_cam_mm"] == pytest.approx(np.hypot(58.0, 36.0))
    assert pushed["passed"] and not pulled["passed"] and not pushed["undercut"]


def test_only_the_pulled_roller_of_the_square_layout_lifts_the_plate(report):
    """The rocker lifts the plate turning clockwise (theta_CG falls from its low-plate to its high-plate value in
    every reading); the arm's turn over the rise, read from the roller centres the cam tool computes at the
    rise's start and end, is clockwise only on the pulled side. So the side that passes the 45 deg limit (pushed)
    lowers the plate, and the one that lifts it fails on the return."""
    from transplanter.cam.synthesis import synthesize
    from transplanter.cam.table5 import PIVOT_C, _cam_problem, perpendicular_layout

    for entry in report["heights_from_datum"]:
        assert entry["theta_cg_deg"]["high"] < entry["theta_cg_deg"]["low"]
    layout = report["perpendicular_layout"]
    pivot = PIVOT_C - np.array(layout["center"])
    for cam in layout["cams"]:
        geometry = synthesize(_cam_problem(pivot, cam["roller_side"] == "pulled", np.radians(36.0))).geometry
        rise = geometry.segment == 0
        arm = geometry.center[rise] - pivot
        turn = np.unwrap(np.arctan2(arm[:, 1], arm[:, 0]))
        assert np.degrees(abs(turn[-1] - turn[0])) == pytest.approx(36.0, abs=0.5)
        assert cam["lifts_plate"] == (turn[-1] < turn[0]) == (cam["roller_side"] == "pulled")
    pulled = layout["cams"][0]
    assert pulled["failures"] and pulled["max_pressure_angle_deg"]["return"] > 45.0
    assert perpendicular_layout(1.0)["cams"][1]["lifts_plate"]      # a plate lifted counterclockwise: pushed


def test_timed_segments_from_the_paper_stages():
    """The paper's stages (110, 80, 85, 85 deg) with a 1:1 chain give its cam program, which the cam tool takes;
    stages that do not make a cam turn at the ratio are refused with the ratio that would."""
    from transplanter import cam
    from transplanter.cam.timing import plate_clearance, timed_segments
    from transplanter.errors import ProblemError

    rows = timed_segments(np.radians([110.0, 80.0, 85.0, 85.0]), 1.0, np.radians(36.0))
    assert [(r["kind"], r["angle_deg"]) for r in rows] == [("rise", 110.0), ("dwell", 80.0), ("return", 85.0),
                                                           ("dwell", 85.0)]
    problem = cam.parse_problem({"cam": {"base_radius": 30.0}, "segments": rows,
                                 "follower": {"kind": "oscillating", "roller_radius": 6.0, "pivot": [70.0, 0.0],
                                              "arm_length": 58.0}})
    assert np.degrees(problem.segments[0].lift) == pytest.approx(36.0)
    halves = timed_segments(np.radians([55.0, 40.0, 42.5, 42.5]), 2.0, np.radians(36.0))
    assert [r["angle_deg"] for r in halves] == pytest.approx([110.0, 80.0, 85.0, 85.0])
    with pytest.raises(ProblemError, match="would be 2"):
        timed_segments(np.radians([55.0, 40.0, 42.5, 42.5]), 1.0, np.radians(36.0))
    assert plate_clearance(-130.0, [-100.0, -121.5, -90.0]) == (8.5, 1)

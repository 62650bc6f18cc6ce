"""Every command's design moves with the motions that leave its problem the same problem (to 1e-9 relative).

Which motions those are depends on what the problem fixes in the world:

- burmester: any similarity (rotation, translation, scale) of the poses; nothing is fixed in the world
  (tests/burmester/test_frame_invariance.py, hypothesis over every example).
- reverse: rotation of the path about the carrier axis, the axis and path moved together, every length scaled
  (tests/reverse/test_frame_invariance.py, hypothesis); the carrier axis is the one fixed point.
- fivebar: rotation of the key poses and return points about the carrier pivot O (the origin), for a problem
  without the fields posed in world axes: ``ranges.x_e``/``x_f`` (x of a hinge), ``requirements`` (horizontal and
  vertical offsets), ``[load]`` (gravity) and ``[support]`` (the soil line); with them a turned problem is another
  problem. Scale with every length (tests/api/test_scale_invariance.py). Translation is not one: O is the origin.
  Here: the solution region (every five-bar judged, its margins and ratios, the hinges turned back) after a turn.
- gear: a shift of the sampled ratio (or spline radius) in the driver's angle gives the same pair turned; scale
  with the module (test_scale_invariance.py). A pitch curve has no world frame; the families given by parameters
  (ellipse, limacon, ...) have no phase to shift.
- cam: the motion program started at another of its base-circle dwells gives the same cam turned; scale with every
  length (test_scale_invariance.py). Rotation of the frame is not one: the follower's line (+y) and pivot are the
  frame, so a turned follower is a problem the file cannot state otherwise.
- pickup: the carrier's start angle turned (the whole mechanism turned about O) with every length scaled and the
  speed scaled moves the tip, its picking point and its speeds with them; "lowest" (the pushing point, gravity)
  is not invariant under a turn, so pushing is given as a carrier turn here.
- parallelogram: l2, l5 and l6 only translate the duckbill's path (the onion-transplanter paper), and a speed
  scale of the driver and the machine together scales time: depth, vertical range and spacing stay, speeds scale.
  Rotation is not one (the soil, the travel direction and the planting depth are world directions), nor is a
  change of scale (the module and the depth window are fixed in mm by the paper's design).
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from transplanter import cam, fivebar, gears, parallelogram, pickup
from transplanter.toml_fields import read_toml

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
RELATIVE = 1e-9


def _copy(data: dict) -> dict:
    return json.loads(json.dumps(data))


def _turned(points, angle: float) -> np.ndarray:
    c, s = np.cos(angle), np.sin(angle)
    points = np.asarray(points, float)
    return np.stack([c * points[..., 0] - s * points[..., 1], s * points[..., 0] + c * points[..., 1]], -1)


def _same_angle_deg(first, second):
    """Angles in degrees equal modulo a turn, to RELATIVE of a turn."""
    difference = np.mod(np.asarray(first, float) - np.asarray(second, float) + 180.0, 360.0) - 180.0
    np.testing.assert_allclose(difference, 0.0, rtol=0, atol=RELATIVE * 360.0)


def test_fivebar_region_turns_with_the_poses_about_the_carrier_pivot():
    from transplanter.fivebar.region import solution_region

    data = read_toml(EXAMPLES / "vegetable_planting.toml")
    for key in ("x_e", "x_f"):                     # x of a hinge: posed in world axes
        del data["ranges"][key]
    angle = np.radians(37.0)
    turned = _copy(data)
    for row in turned["key_poses"] + turned["return_points"]:
        row["x"], row["y"] = _turned([row["x"], row["y"]], angle).tolist()
        if "angle_deg" in row:
            row["angle_deg"] += 37.0
    original, moved = (solution_region(fivebar.parse_problem(d)) for d in (data, turned))
    assert moved.pair_defects == original.pair_defects and len(moved.feasible) == len(original.feasible) > 0
    assert (moved.receiving.kept.sum(), moved.carrier.kept.sum()) == (original.receiving.kept.sum(),
                                                                      original.carrier.kept.sum())
    for one, other in zip(original.feasible, moved.feasible, strict=True):
        assert other.min_margin == pytest.approx(one.min_margin, rel=RELATIVE)
        np.testing.assert_allclose(other.ratio_range, one.ratio_range, rtol=RELATIVE)
        np.testing.assert_allclose(_turned(other.mech.hinge_b, -angle), one.mech.hinge_b, rtol=0,
                                   atol=RELATIVE * np.abs(one.mech.hinge_b).max())
        for name in ("carrier_length", "rod_length", "receiving_length", "e_local", "f_local"):
            np.testing.assert_allclose(getattr(other.mech, name), getattr(one.mech, name), rtol=RELATIVE)


def test_gear_pair_of_a_ratio_shifted_in_the_driver_angle():
    data = read_toml(EXAMPLES / "gear_ratio.toml")
    shifted = _copy(data)
    shifted["driver"]["phi_deg"] = [phi + 45.0 for phi in data["driver"]["phi_deg"]]
    original, moved = (gears.synthesize(gears.parse_problem(d)).to_json() for d in (data, shifted))
    size = original["center_distance"]
    for report in (original, moved):           # accuracy measures: at rounding, not compared with each other
        assert abs(report.pop("closure_error")) < RELATIVE and report.pop("rolling_mismatch_mm") < RELATIVE * size
        report.pop("timings_s")
    assert _numbers(moved) == pytest.approx(_numbers(original), rel=RELATIVE)


def _numbers(report) -> list[float]:
    """Every number of a report, in order (its keys and text compared alike)."""
    if isinstance(report, dict):
        return [value for key in sorted(report) for value in _numbers(report[key])]
    if isinstance(report, list):
        return [value for item in report for value in _numbers(item)]
    return [float(report)] if isinstance(report, (int, float)) and not isinstance(report, bool) else []


def test_cam_program_started_at_its_other_dwell():
    """The flat-faced example (rise 90, dwell 45, return 90, dwell 135 deg) started at the last dwell: the same cam
    turned by 135 deg. The nearest point of the profile is not compared by place: it lies anywhere on the base
    circle's dwell."""
    data = read_toml(EXAMPLES / "cam_flat_faced.toml")
    started = _copy(data)
    started["segments"] = data["segments"][-1:] + data["segments"][:-1]
    original, moved = (cam.synthesize(cam.parse_problem(d)).to_json() for d in (data, started))
    shift = data["segments"][-1]["angle_deg"]
    for key in ("base_radius_mm", "nearest_profile_mm", "max_pressure_angle_deg", "min_curvature_radius_mm"):
        one, other = original[key], moved[key]
        if isinstance(one, dict):
            places, other_places = one.get("at_deg", {}), other.get("at_deg", {})
            for name, place in places.items() if key != "nearest_profile_mm" else ():
                assert (other_places[name] is None) == (place is None), (key, name)   # None: no such place
                if place is not None:
                    _same_angle_deg(other_places[name], place + shift)
            one, other = ({name: value for name, value in d.items() if name != "at_deg"} for d in (one, other))
        assert _numbers(other) == pytest.approx(_numbers(one), rel=RELATIVE), key


def test_pickup_turned_scaled_and_sped_up():
    data = read_toml(EXAMPLES / "pickup_forward.toml")
    data["angles"]["pushing"] = 272.5                  # "lowest" is a world direction (gravity)
    angle, scale, speed = 37.0, 2.5, 3.0
    moved = _copy(data)
    moved["carrier"]["start_deg"] += angle
    moved["carrier"]["speed_rpm"] = data["carrier"].get("speed_rpm", 60.0) * speed
    for table, key in (("carrier", "first_length"), ("carrier", "second_length"), ("arm", "length")):
        moved[table][key] *= scale
    one, other = (pickup.synthesize(pickup.parse_problem(d)).to_json() for d in (data, moved))
    for point in ("picking", "pushing"):
        assert other[point]["carrier_turn_deg"] == pytest.approx(one[point]["carrier_turn_deg"], rel=RELATIVE)
        np.testing.assert_allclose(_turned(other[point]["tip_mm"], -np.radians(angle)) / scale, one[point]["tip_mm"],
                                   rtol=0, atol=RELATIVE * np.abs(one[point]["tip_mm"]).max())
        _same_angle_deg(other[point]["needle_direction_deg"], one[point]["needle_direction_deg"] + angle)
    np.testing.assert_allclose(np.divide(other["tip_speed_range_mm_s"], scale * speed), one["tip_speed_range_mm_s"],
                               rtol=RELATIVE)
    np.testing.assert_allclose(other["planet_turn_range_deg"], one["planet_turn_range_deg"], rtol=0, atol=1e-9)


def test_parallelogram_translating_links_and_time_scale():
    """The published onion design with l2, l5, l6 changed (the path moves) and the driver and the machine three
    times as fast (time runs three times as fast): the same depth, vertical range and spacing, speeds three times."""
    from transplanter.parallelogram.evaluation import evaluate

    data = read_toml(EXAMPLES / "onion_published.toml")
    moved = _copy(data)
    moved["design"].update(l2=data["design"]["l2"] + 40.0, l5=data["design"]["l5"] + 7.0,
                           l6=data["design"]["l6"] - 20.0)
    machine = moved.setdefault("machine", {})
    machine["driver_speed_rpm"] = data.get("machine", {}).get("driver_speed_rpm", 60.0) * 3
    machine["forward_speed_mm_s"] = data.get("machine", {}).get("forward_speed_mm_s", 300.0) * 3
    problems = [parallelogram.parse_problem(d) for d in (data, moved)]
    one, other = (evaluate(problem, problem.design) for problem in problems)
    for name, power in (("depth", 0), ("vertical_range", 0), ("spacing", 0), ("center_distance", 0),
                        ("vx_release", 1), ("ax_release", 2), ("planting_time", -1)):
        assert getattr(other, name) == pytest.approx(getattr(one, name) * 3.0**power, rel=RELATIVE, abs=1e-12), name

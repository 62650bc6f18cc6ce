"""Key poses as bands and the relative requirements between them (Wang et al. 2025 section 3.1): how they are
read and refused, and the design the bands example gets, each checked on the design itself."""
import json
from pathlib import Path

import numpy as np
import pytest

from transplanter.cli import main
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.fivebar import load_problem, parse_problem, synthesize
from transplanter.fivebar.alternatives import transmission_angles
from transplanter.fivebar.key_pose_bands import Requirements
from transplanter.toml_fields import read_toml

ROOT = Path(__file__).resolve().parents[2]
BANDS = ROOT / "examples/vegetable_planting_bands.toml"


def _edited(change):
    data = read_toml(BANDS)
    change(data)
    return data


@pytest.mark.parametrize("change, field", [
    (lambda d: d["key_poses"][1].update(x=[-46.1, -56.1]), r"key_poses\[1\]\.x"),
    (lambda d: d["key_poses"][0].update(carrier_turn_deg=[0.0, 5.0]), r"key_poses\[0\]\.carrier_turn_deg"),
    (lambda d: d["key_poses"][2].update(carrier_turn_deg=[10.0, 60.0]), r"key_poses\[\]\.carrier_turn_deg"),
    (lambda d: d["requirements"].update(min_stroke_mm=200.0), r"requirements\.min_stroke_mm"),
    (lambda d: d["requirements"].update(max_offset_from_first_mm=[100.0, 10.0]),
     r"requirements\.max_offset_from_first_mm"),
    (lambda d: d["requirements"].update(max_last_step_mm=20.0), r"requirements\.max_last_step_mm"),
    (lambda d: d["conditions"].update(min_transmission_angle_deg=90.0), r"conditions\.min_transmission_angle_deg"),
    (lambda d: d["conditions"].update(min_transmission_angle_deg=-1.0), r"conditions\.min_transmission_angle_deg"),
])
def test_bands_and_requirements_no_pose_can_meet_are_refused_naming_the_field(change, field):
    with pytest.raises(ProblemError, match=field) as error:
        parse_problem(_edited(change), "bands.toml")
    assert str(error.value).startswith("bands.toml: ") and "\n" not in str(error.value)


def test_a_band_is_read_in_mm_and_radians_with_its_centre_as_the_pose_the_region_starts_from():
    problem = load_problem(BANDS)
    bands = problem.pose_bands
    assert bands.banded.sum() == 9 and not bands.banded[0].any() and not bands.banded[:, 3].any()
    assert bands.low[1, 2] == pytest.approx(np.radians(90.0)) and bands.high[1, 2] == pytest.approx(np.radians(100.0))
    assert problem.poses[1, 0] == pytest.approx(-51.1) and problem.poses[1, 2] == pytest.approx(np.radians(95.0))
    assert bands.field(problem.labels, 1, 2) == "key_poses.P2.angle_deg"


def test_requirements_are_the_offsets_stroke_and_last_step_of_the_paper():
    """On Table 1 of Wang et al. 2025: P2-P4 lie 28.0, 81.4, 115.8 mm left and 4.9, 5.1, 0.7 mm from P1; the
    stroke P1-P4 is 115.8 mm and P4 lies 34.4 mm left of P3."""
    table1 = np.array([[-23.1, -309.7], [-51.1, -314.6], [-104.5, -314.8], [-138.9, -309.0]])
    rows = Requirements((130.0, 10.0), 110.0, 40.0).rows(list(table1[:, 0]), list(table1[:, 1]), 1.0)
    values = {}
    for name, value, _, _ in rows:
        values.setdefault(name, []).append(value)
    assert values["requirements.max_offset_from_first_mm"] == pytest.approx([-28.0, -4.9, -81.4, -5.1, -115.8, 0.7])
    assert values["requirements.min_stroke_mm"] == pytest.approx([115.8])
    assert values["requirements.max_last_step_mm"] == pytest.approx([34.4])
    assert Requirements((130.0, 10.0), 110.0, 40.0).broken(np.c_[table1, np.zeros(4)], 1.0) == []
    assert Requirements((100.0, 10.0), 120.0, 30.0).broken(np.c_[table1, np.zeros(4)], 1.0) == [
        "requirements.max_offset_from_first_mm", "requirements.min_stroke_mm", "requirements.max_last_step_mm"]


def test_drawn_pose_sets_lie_in_the_bands_and_meet_the_requirements(rng):
    problem = load_problem(BANDS)
    for _ in range(50):
        drawn = problem.pose_bands.sample(rng, problem.requirements, problem.stroke_direction)
        assert np.all(drawn >= problem.pose_bands.low) and np.all(drawn <= problem.pose_bands.high)
        assert problem.requirements.broken(drawn[:, :3], problem.stroke_direction) == []


def test_bands_no_region_can_meet_exit_with_the_condition_that_binds_most_often():
    """|EP| held to 55-56 mm leaves no five-bar at any pose set of the bands: the error counts the sets tried
    and names the condition that emptied the most regions."""
    data = _edited(lambda d: (d["ranges"].update(ep=[55.0, 56.0]), d["region"].update(band_samples=3, samples=300)))
    with pytest.raises(InfeasibleError, match=r"4 tried .*binds most often: .*\(emptied \d of the 4 pose sets tried\)"):
        synthesize(parse_problem(data, "narrow.toml"))


@pytest.fixture(scope="module")
def banded():
    """The bands example's design (its tolerance analysis is not read here)."""
    return synthesize(load_problem(BANDS), tolerance=False)


def test_the_bands_design_meets_its_chosen_poses_inside_the_bands_and_every_requirement(banded):
    problem = load_problem(BANDS)
    design = banded.design
    chosen = np.c_[design.poses, design.carrier_turns]
    width = problem.pose_bands.high - problem.pose_bands.low
    assert np.all(chosen >= problem.pose_bands.low - 1e-9 * (1 + width))
    assert np.all(chosen <= problem.pose_bands.high + 1e-9 * (1 + width))
    assert problem.requirements.broken(design.poses, problem.stroke_direction, slack=1e-9) == []
    # met after the toothed gears roll (the verification rolls the pitch curves, then closes the linkage)
    assert np.abs(banded.verification.key_position_errors_mm).max() < 1e-9
    assert np.abs(banded.verification.key_angle_errors_deg).max() < 1e-9
    assert np.allclose(banded.problem.poses, design.poses) and np.allclose(banded.problem.carrier_turns,
                                                                           design.carrier_turns)


def test_the_bands_design_has_a_transmission_angle_of_at_least_40_deg_measured_on_its_hinges(banded):
    """The smallest angle between EF and BE at E over a turn, measured by atan2 on the hinges of the forward
    kinematics at 3600 turns: at least 40 deg, the usual floor for a linkage (26.8 deg on the fixed poses
    before the NLP maximised it)."""
    design = banded.design
    turns = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    state = design.mech.forward(turns, design.relative_angle.evaluate(turns))
    at_e, _ = transmission_angles(design.mech, state)
    assert np.degrees(at_e.min()) >= 40.0
    assert banded.chosen.transmission_angle == pytest.approx(at_e.min(), abs=1e-12)


def test_the_band_edges_a_design_sits_on_are_named_as_the_file_names_them(banded):
    problem = load_problem(BANDS)
    design = banded.design
    chosen = np.c_[design.poses[:, :2], np.degrees(design.poses[:, 2]), np.degrees(design.carrier_turns)]
    named = [bound for bound in banded.chosen.active_bounds if bound.name.startswith("key_poses.")]
    assert named
    for bound in named:
        _, label, quantity = bound.name.split(".")
        i, q = problem.labels.index(label), ("x", "y", "angle_deg", "carrier_turn_deg").index(quantity)
        assert bound.value == pytest.approx(chosen[i, q], abs=1e-9) and bound.value == pytest.approx(bound.limit,
                                                                                                     abs=1e-6)


def test_the_report_lists_the_chosen_poses_the_pose_sets_tried_the_pressure_angles_and_the_load(banded):
    report = json.loads(json.dumps(banded.to_json(), allow_nan=False))
    design = banded.design
    chosen = report["chosen_key_poses"]
    assert [row["label"] for row in chosen] == ["P1", "P2", "P3", "P4"]
    assert [row["x"] for row in chosen] == pytest.approx(design.poses[:, 0].tolist(), abs=1e-12)
    assert [row["angle_deg"] for row in chosen] == pytest.approx(np.degrees(design.poses[:, 2]).tolist(), abs=1e-9)
    assert chosen[0]["banded"] == [] and chosen[1]["banded"] == ["x", "y", "angle_deg"]
    tried = report["key_pose_sets"]
    assert tried[-1]["feasible_five_bars"] > 0 and all(t["emptied_by"] for t in tried[:-1])
    assert tried[0]["poses"][1]["x"] == pytest.approx(-51.1)             # the bands' centres come first
    assert {b["bound"] for b in report["active_bounds"]} >= {b.name for b in banded.chosen.active_bounds}
    assert len(report["gear_pressure_angle_max_deg"]) == 2
    assert max(report["gear_pressure_angle_max_deg"]) <= report["gear_pressure_angle_limit_deg"] * (1 + 1e-3)
    load = report["load"]
    assert load["resisting_n"] == 20.0 and set(load["hinge_force_peak_n"]) == {"O", "A", "B", "E", "F"}
    assert abs(load["be_force_peak_n"]) > 0 and abs(load["carrier_torque_peak_nm"]) > 0
    assert report["transmission_angle_min_deg"] == pytest.approx(np.degrees(banded.chosen.transmission_angle))
    assert report["closure_angle_min_deg"] == pytest.approx(np.degrees(banded.chosen.closure_angle))


def test_a_band_upside_down_exits_2_with_one_line_and_writes_nothing(tmp_path, capsys):
    text = BANDS.read_text().replace("x = [-56.1, -46.1]", "x = [-46.1, -56.1]")
    path = tmp_path / "upside_down.toml"
    path.write_text(text)
    out = tmp_path / "out"
    assert main(["fivebar", str(path), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "key_poses[1].x = [-46.1, -56.1]" in err and "low <= high" in err
    assert not out.exists()

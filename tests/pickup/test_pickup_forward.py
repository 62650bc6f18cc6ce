"""The pick-up mechanism forward (the cusp-pitch-curve paper, section 6, eq 15): circles, rates, closure, bad
input, command."""
import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from transplanter import pickup
from transplanter.cli import main
from transplanter.errors import InfeasibleError, ProblemError
from transplanter.gears.pair import driven_turn
from transplanter.geometry.turn_quadrature import panels

EXAMPLE = Path(__file__).resolve().parents[2] / "examples/pickup_forward.toml"


def circles(**changes):
    data = {"carrier": {"first_length": 50.0, "second_length": 40.0, "bend_deg": 150.0, "start_deg": 10.0},
            "arm": {"length": 120.0, "mounting_deg": 30.0},
            "stage1": {"driver": {"family": "ellipse", "semi_major_axis": 20.0, "eccentricity": 0.0}},
            "stage2": {"driver": {"family": "ellipse", "semi_major_axis": 15.0, "eccentricity": 0.0}}}
    for key, value in changes.items():
        data[key] = value
    return data


def test_equal_circles_keep_the_arm_parallel():
    """1:1 circles: the planet turns back by the carrier's turn, so the arm keeps its direction delta0 + alpha0 +
    phi0 and the tip is O2 plus a fixed vector (eq 15 built by hand)."""
    result = pickup.synthesize(pickup.parse_problem(circles()))
    c = result.carrier_turns
    assert np.allclose(result.planet_turn, -c, atol=1e-9)
    start, bend, mount = np.radians([10.0, 150.0, 30.0])
    expected = (50 * np.c_[np.cos(start + c), np.sin(start + c)] + 40 * np.c_[np.cos(start + c + bend),
                                                                          np.sin(start + c + bend)]
                + 120 * np.array([np.cos(start + bend + mount), np.sin(start + bend + mount)]))
    assert np.abs(result.tip - expected).max() < 1e-9
    angles = result.to_json()
    assert angles["picking"]["angle_deg"] == pytest.approx(np.degrees(np.arctan(abs(np.tan(start + bend + mount)))))


def test_velocity_and_planet_rate_agree_with_differences_of_the_path():
    result = pickup.synthesize(pickup.load_problem(EXAMPLE))
    dc = result.carrier_turns[1] - result.carrier_turns[0]
    dt = dc / result.problem.speed
    psi = np.unwrap(result.planet_turn)
    rate = (psi[2:] - psi[:-2]) / (2 * dc)
    assert np.abs(rate - result.planet_rate[1:-1]).max() < 2e-3 * np.abs(result.planet_rate).max()
    velocity = (result.tip[2:] - result.tip[:-2]) / (2 * dt)
    scale = np.hypot(*result.velocity.T).max()
    smooth = np.abs(np.diff(result.planet_rate, 2)) < 1e-3 * np.abs(result.planet_rate).max()   # away from corners
    assert np.abs(velocity - result.velocity[1:-1])[smooth].max() < 2e-3 * scale
    report = result.to_json()
    assert report["planet_turn_per_carrier_turn_deg"] == pytest.approx(-360.0, abs=1e-6)
    assert max(abs(e) for e in result.closure_errors) < 1e-9
    assert [s["center_distance_mm"] for s in report["stages"]] == pytest.approx([55.0, 45.0], rel=1e-12)


@pytest.mark.parametrize("change,message", [
    ({"stage2": {}}, "stage2.driver = None: expected a [driver] table"),
    ({"stage1": {"driver": {"family": "ratio", "expression": "1"}}}, "stage1.driver.family = 'ratio'"),
    ({"carrier": {"first_length": -5.0, "second_length": 40.0}}, "carrier.first_length = -5.0: expected a positive"),
    ({"angles": {"picking": "top"}}, "angles.picking = 'top'"),
    ({"angles": {"picking": 2e6}}, "angles.picking = 2000000.0: expected \"farthest\" or a carrier turn in degrees "
                                   "from the start, within ±1e+06"),
    ({"carrier": {"first_length": 50.0, "second_length": 40.0, "speed_rpm": 0.0}},
     "carrier.speed_rpm = 0.0: expected a speed other than 0"),
])
def test_bad_input(change, message):
    with pytest.raises(ProblemError) as error:
        pickup.parse_problem(circles(**change), "p.toml")
    assert message in str(error.value) and "\n" not in str(error.value)


def test_a_stage_whose_radius_nearly_reaches_the_centre_is_refused_naming_it():
    """e = 0.999: r_min / r_max = (1 - e) / (1 + e) = 5e-4, below the thousandth every pitch curve keeps (without
    this check closure fails with a message about pair.center_distance, a field a pick-up file does not have)."""
    data = circles(stage1={"driver": {"family": "ellipse", "semi_major_axis": 20.0, "eccentricity": 0.999}})
    with pytest.raises(ProblemError, match=r"p.toml: stage1.driver: the pitch radius reaches .* expected at least "
                                           r"0.001 of the largest"):
        pickup.synthesize(pickup.parse_problem(data, "p.toml"))


def test_a_stage_of_order_two_is_refused():
    data = circles(stage1={"driver": {"family": "higher_order_ellipse", "semi_major_axis": 20.0,
                                      "eccentricity": 0.1, "order": 2}})
    with pytest.raises(InfeasibleError, match="stage1.driver has order 2"):
        pickup.synthesize(pickup.parse_problem(data, "p.toml"))


def test_command_writes_the_report(tmp_path, capsys):
    code = main(["pickup", str(EXAMPLE), "--json", "--out", str(tmp_path / "out"), "--no-animation"])
    assert code == 0
    report = json.loads(capsys.readouterr().out)
    assert {"picking", "pushing", "tip_speed_range_mm_s"} <= set(report)
    assert (tmp_path / "out" / "pickup_path.png").exists()


@pytest.fixture(scope="module")
def turned():
    """The equal circles turned (a quick pick-up that passes)."""
    return pickup.synthesize(pickup.parse_problem(circles(), "circles.toml"))


def test_a_mechanism_whose_gears_close_and_whose_tip_is_reached_passes(turned):
    assert turned.passed and turned.failures == [] and turned.produced


@pytest.mark.parametrize("stage", ["stage_one", "stage_two"])
def test_a_stage_that_does_not_close_fails(turned, stage):
    """The stage's pair as built 1 % beyond its closing centre distance: its driven gear misses a whole turn by
    what the turn quadrature gives there (the pair is otherwise unchanged, so only this check can fail)."""
    pair = getattr(turned, stage)
    wide = 1.01 * pair.center_distance
    closure = driven_turn(pair.driver, wide, panels(pair.driver.breaks)) - 2 * np.pi
    failing = dataclasses.replace(turned, **{stage: dataclasses.replace(pair, closure_error=closure)})
    name = {"stage_one": "stage1", "stage_two": "stage2"}[stage]
    assert len(failing.failures) == 1 and failing.failures[0].startswith(f"{name} does not close")
    assert f"{abs(closure) * pair.center_distance:.3g} mm" in failing.failures[0]


def test_a_tip_lost_at_one_position_fails(turned):
    """One carrier position where the tip and its velocity are not numbers (an arm that could not be placed)."""
    tip, velocity = turned.tip.copy(), turned.velocity.copy()
    tip[100], velocity[100] = np.nan, np.nan
    failing = dataclasses.replace(turned, tip=tip, velocity=velocity)
    assert failing.failures == [f"the tip path is not reached at 1 of {len(tip)} carrier positions, first at carrier "
                                f"turn {np.degrees(turned.carrier_turns[100]):.2f} deg (tip or velocity not finite)"]


def test_a_planet_that_does_not_come_back_after_a_carrier_turn_fails(turned):
    """A planet that turns half a turn against the carrier per carrier turn (a stage of order two would): the tip
    does not come back to where it started."""
    failing = dataclasses.replace(turned, planet_turn_per_turn=-np.pi)
    assert len(failing.failures) == 1 and "turns -180 deg against the carrier per carrier turn" in failing.failures[0]
    arc = turned.problem.arm_length * np.pi
    assert f"the needle is +180 deg off its start, {arc:.3g} mm of arc" in failing.failures[0]


def test_a_failing_pickup_exits_1_with_failed_files(turned, tmp_path, monkeypatch, capsys):
    failing = dataclasses.replace(turned, planet_turn_per_turn=-np.pi)
    monkeypatch.setattr(pickup, "synthesize", lambda problem: failing)
    out = tmp_path / "out"
    assert main(["pickup", str(EXAMPLE), "--json", "--out", str(out), "--no-animation"]) == 1
    captured = capsys.readouterr()
    report = json.loads(captured.out)
    assert report["status"] == "FAILED" and report["failures"] == failing.failures
    assert captured.err == f"transplanter: failed: circles.toml: {failing.failures[0]}\n"
    assert {p.name for p in out.iterdir()} == {"FAILED-report.json", "FAILED-report.md", "FAILED-pickup_path.png",
                                               "FAILED-pickup_speed.png"}

"""The built reverse train and arm as a function of their manufactured dimensions (``reverse.tolerance_model``):
the model at its nominal dimensions is the synthesis's own round trip, its exact Jacobian equals central
differences of the forward model and of the verification's tip, the gears' phases move the arm as the designed
motion says, a planted change moves the key points by J delta to second order, and first order meets the Monte
Carlo at the default tolerances and parts from it at ten times those; the same for the sun-idler-planet train,
and the path accuracy the analysis judges built trains by."""
import dataclasses
import json
import tomllib
from pathlib import Path

import numpy as np
import pytest

from tests.tolerance.model_checks import (
    assert_first_order_meets_monte_carlo,
    assert_jacobian_is_central_differences,
    assert_planted_change_is_second_order,
)
from transplanter import reverse
from transplanter.errors import ProblemError
from transplanter.reverse.idler_train import roll_idler_train
from transplanter.reverse.synthesis import _analysed as analysed
from transplanter.reverse.tolerance_model import DIMENSION_NAMES, IDLER_DIMENSION_NAMES, PATH_ACCURACY, TURN_SAMPLES
from transplanter.reverse.verification import CHECK_POINTS, rebuild_tip
from transplanter.tolerance import ToleranceSettings, analyse

ROOT = Path(__file__).resolve().parents[2]
RICE = ROOT / "examples/rice_hoe_reverse.toml"
PICKUP = ROOT / "examples/pickup_arm_reverse.toml"
pytestmark = pytest.mark.filterwarnings("error")      # a numpy warning is a failure


@pytest.fixture(scope="module", params=[RICE, PICKUP], ids=["straight carrier", "bent carrier"])
def result(request):
    return request.getfixturevalue("rice_result" if request.param == RICE else "pickup_result")


@pytest.fixture(scope="module")
def model(result):
    return result.tolerance_model()


@pytest.fixture(scope="module")
def jacobian(model):
    return model.jacobian()


def _tip(result, model, planet_turns):
    """The tip by the verification's own route (``rebuild_tip``) at the model's turns, in the problem's frame."""
    turns = np.radians(model.turns_deg)
    return (rebuild_tip(result.motion, result.geometry, turns, planet_turns) + result.problem.pivot).T


def test_nominal_built_mechanism_is_the_synthesised_one(result, model):
    motion = model.evaluate(model.nominal)
    reach = result.motion.carrier_length + result.motion.arm_length
    check = result.verification
    step = CHECK_POINTS // TURN_SAMPLES
    assert np.abs(motion[:2, model.whole_turn].T - check.reproduced[::step] - result.problem.pivot).max() < 1e-9 * reach
    assert np.abs(motion[:2, model.whole_turn].T - check.target[::step] - result.problem.pivot).max() < 1e-8 * reach
    radii = np.linalg.norm(motion[:2, :2].T - result.problem.pivot, axis=1)
    assert radii == pytest.approx(result.extremes, rel=1e-9)
    theta, gamma = result.motion.angles(result.motion.parameter_at(np.radians(model.turns_deg)))
    assert np.abs(np.angle(np.exp(1j * (motion[2] - theta - gamma)))).max() < 1e-9
    assert model.names == DIMENSION_NAMES and model.key_labels == ("farthest", "nearest")


def test_numpy_and_casadi_motions_agree(model, rng):
    dimensions = model.nominal + model.tolerances * rng.uniform(-1, 1, (4, len(model.nominal)))
    for row, motion in zip(dimensions, model.sampled(dimensions), strict=True):
        assert np.allclose(model.evaluate(row), motion, rtol=1e-12, atol=1e-10)


def test_sensitivities_equal_central_differences_of_the_forward_model(model, jacobian):
    n = len(model.nominal)
    step = 1e-2 * model.tolerances
    motion = model.sampled(model.nominal + np.vstack([np.diag(step), -np.diag(step)]))
    difference = (motion[:n] - motion[n:]) / (2 * step[:, None, None])             # (n, rows, T)
    exact = np.moveaxis(jacobian, -1, 0)
    scale = np.abs(exact).max(axis=2, keepdims=True)
    assert np.all(np.abs(exact - difference) <= 1e-6 * scale + 1e-12), np.max(np.abs(exact - difference) / scale)


def test_arm_length_sensitivity_is_the_arm_direction(result, model, jacobian):
    """d tip / d l is the unit vector along the arm, and l does not turn it: the two-link tip of the
    verification with the arm lengthened."""
    j = model.names.index("arm_length")
    angle = model.evaluate(model.nominal)[2]
    assert np.abs(jacobian[:2, :, j] - np.vstack([np.cos(angle), np.sin(angle)])).max() < 1e-12
    assert np.abs(jacobian[2, :, j]).max() < 1e-12


def test_gear_phases_move_the_arm_as_the_designed_motion_says(result, model):
    """The planet's phase turns the arm by it exactly; the sun's shifts the carrier turn the train sees,
    chi(c + phase), which the model's second-order expansion meets to third order in the phase (but at the
    touches of the reach circles, where chi'' changes within the phase and the miss is of second order)."""
    relative, turns = result.relative, np.radians(model.turns_deg)
    reach = result.motion.carrier_length + result.motion.arm_length

    def miss(name, phase):
        dimensions = model.nominal.copy()
        dimensions[model.names.index(name)] = phase
        planet_turns = relative.evaluate(turns + np.radians(phase if name == "phase_sun" else 0.0))
        planet_turns += np.radians(phase if name == "phase_planet" else 0.0) - relative.evaluate(np.zeros(1))[0]
        return np.linalg.norm(model.sampled(dimensions[None])[0][:2] - _tip(result, model, planet_turns), axis=0)

    assert miss("phase_planet", 0.1).max() < 1e-9 * reach
    sun = [miss("phase_sun", phase) for phase in (0.1, 0.05)]
    assert sun[0].max() < 1e-6 * reach                   # at the default phase tolerance: 2e-5 mm of 254 mm
    assert 6 < np.median(sun[0]) / np.median(sun[1]) < 10


def test_mirrored_path_mirrors_the_sensitivities(rice_result):
    """The rice hoe (conftest's ``rice_result``) mirrored in x, run the other way round, is the mirror image of the
    design: every sensitivity mirrors (x and the arm's angle change sign; an x offset and the bend, angles and
    offsets counted counterclockwise or along x, change sign with them), which holds the rotation direction's signs
    to account."""
    data = tomllib.loads(RICE.read_text())
    data["trajectory"]["points"] = [[-x, y] for x, y in data["trajectory"]["points"]]
    data["arm"]["direction"] = "counterclockwise"
    mirror = reverse.synthesize(reverse.parse_problem(data, "mirrored rice"), tolerance=False)
    model = rice_result.tolerance_model()
    jacobians = [model.jacobian(), mirror.tolerance_model().jacobian()]
    odd = [name in ("carrier_bend", "clearance_pivot_x", "clearance_planet_x") for name in model.names]
    mirrored = jacobians[0] * np.array([-1, 1, -1])[:, None, None] * np.where(odd, -1, 1)
    assert np.abs(jacobians[1] - mirrored).max() < 1e-6 * np.abs(jacobians[0]).max()


def test_planted_change_moves_the_key_points_by_j_delta_to_second_order(model, jacobian):
    k = len(model.key_labels)
    nominal = model.sampled(model.nominal[None])[0][:2, :k]
    j = model.names.index("carrier_bend")
    misses = []
    for delta in (0.25, 0.5):
        dimensions = model.nominal.copy()
        dimensions[j] += delta
        moved = model.sampled(dimensions[None])[0][:2, :k]
        predicted = nominal + jacobian[:2, :k, j] * delta
        misses.append(np.abs(moved - predicted).max())
        assert misses[-1] < 0.02 * np.abs(jacobian[:2, :k, j] * delta).max()
    assert 3.5 < misses[1] / misses[0] < 4.5             # the miss is of second order in delta


@pytest.fixture(scope="module")
def analysis(model):
    return analyse(model)


def test_first_order_meets_the_monte_carlo_at_the_default_tolerances(analysis):
    position, angle = analysis.disagreement()
    assert np.all(position <= 0.10) and np.all(angle <= 0.10), (position, angle)
    assert "agree within 10 % at every key pose" in "\n".join(analysis.to_markdown())


def test_first_order_holds_at_ten_times_the_tolerances_and_parts_at_a_hundred(model):
    """The tip moves with the arm's angle, which the dimensions move almost linearly: first order holds at ten
    times the default tolerances and parts from the Monte Carlo where the arm turns by tens of degrees."""
    def scaled(factor):
        return analyse(model, ToleranceSettings({d.name: factor * d.tolerance for d in model.dimensions},
                                                samples=2000))

    ten = scaled(10)
    assert all(pose["first_order_holds"] for pose in ten.to_json()["key_poses"])
    hundred = scaled(100)
    position, _ = hundred.disagreement()
    assert position[0] > 0.10
    assert not hundred.to_json()["key_poses"][0]["first_order_holds"]
    section = "\n".join(hundred.to_markdown())
    assert "First order breaks (Monte Carlo more than 10 % off) at: farthest arm tip" in section
    assert "| arm angle 3σ, first order (deg) |" in section


def test_report_section_and_figures(result, analysis):
    from dataclasses import replace

    done = replace(result, tolerance=analysis)
    report = done.to_json()
    json.dumps(report, allow_nan=False)
    section = report["tolerance"]
    assert [d["name"] for d in section["dimensions"]] == list(DIMENSION_NAMES)
    nominal = {d["name"]: d["nominal"] for d in section["dimensions"]}
    assert nominal["arm_length"] == report["arm_length"]
    assert [nominal["center_distance_L1"], nominal["center_distance_L2"]] == report["center_distances"]
    assert nominal["carrier_bend"] == pytest.approx(report.get("carrier_bend_deg", 0.0), abs=1e-12)
    assert [p["label"] for p in section["key_poses"]] == ["farthest", "nearest"]
    assert set(section["violation_fraction"]) == {"path accuracy"}
    reach = result.motion.carrier_length + result.motion.arm_length
    assert section["path_accuracy_mm"] == pytest.approx(PATH_ACCURACY * reach, rel=1e-12)
    assert "## Tolerances (the built mechanism)" in done.to_markdown()
    assert {"tolerance_trajectory", "tolerance_band", "tolerance_contributions"} <= set(done.draw_figures())
    assert "tolerance" not in result.to_json() and "tolerance_band" not in result.draw_figures()


def test_a_train_below_iso_2768_sizes_says_why_it_has_no_analysis_until_the_tolerances_are_given():
    data = tomllib.loads(RICE.read_text())
    data["trajectory"]["points"] = [[x / 1000, y / 1000] for x, y in data["trajectory"]["points"]]
    # one train, analysed as the synthesis's last step analyses it, with the problem's own tolerances table and with
    # one that gives the tolerances (the table changes no dimension)
    train = reverse.synthesize(reverse.parse_problem(data, "micro"), tolerance=False)
    result = analysed(train)
    assert result.tolerance is None and not result.failures
    assert "no general tolerance for a length of 0.162 mm" in result.to_json()["tolerance_note"]
    assert "- Tolerances: no tolerance analysis" in result.to_markdown()
    data["tolerances"] = {"arm_length": 1e-3, "center_distance_L1": 1e-3, "center_distance_L2": 1e-3,
                          "carrier_bend": 0.5, "samples": 1000}
    given = analysed(dataclasses.replace(train, problem=reverse.parse_problem(data, "micro")))
    assert given.tolerance is not None and given.tolerance_note == ""


@pytest.fixture(scope="module")
def idler_result():
    """The rice hoe on the rice-transplanter paper's sun-idler-planet train."""
    data = tomllib.loads(RICE.read_text())
    data["train"] = {"topology": "sun-idler-planet"}
    return reverse.synthesize(reverse.parse_problem(data, "idler"), tolerance=False)


@pytest.fixture(scope="module")
def idler_analysis(idler_result):
    return analyse(idler_result, ToleranceSettings(samples=2000))


def test_idler_train_at_its_nominal_dimensions_is_the_verified_one(idler_result, idler_analysis):
    model = idler_analysis.model
    motion = model.evaluate(model.nominal)
    reach = idler_result.motion.carrier_length + idler_result.motion.arm_length
    check, step = idler_result.verification, CHECK_POINTS // TURN_SAMPLES
    assert np.abs(motion[:2, model.whole_turn].T - check.reproduced[::step] - idler_result.problem.pivot).max() \
        < 1e-9 * reach
    assert model.names == IDLER_DIMENSION_NAMES


def test_idler_train_sensitivities_equal_central_differences(idler_analysis):
    assert_jacobian_is_central_differences(idler_analysis)


def test_idler_train_sun_phase_rolls_the_train_from_a_turned_sun(idler_result, idler_analysis):
    """The sun's phase shifts the carrier turn the rolled train sees, chi(c + phase): the model's second-order
    expansion of the idler's and the planet's turns meets the train rolled again to third order in the phase."""
    model = idler_analysis.model
    turns = np.radians(model.turns_deg)
    train = idler_result.train

    def miss(phase):
        dimensions = model.nominal.copy()
        dimensions[model.names.index("phase_sun")] = phase
        chi = roll_idler_train(train.stage_one, train.planet, np.r_[0.0, turns + np.radians(phase)])[0]
        rolled = _tip(idler_result, model, chi[1:] - chi[0])
        return np.linalg.norm(model.sampled(dimensions[None])[0][:2] - rolled, axis=0)

    misses = [miss(phase) for phase in (0.1, 0.05)]
    assert 6 < np.median(misses[0]) / np.median(misses[1]) < 10


def test_idler_train_planted_change_and_monte_carlo(idler_result, idler_analysis):
    assert_planted_change_is_second_order(idler_analysis, "carrier_bend", (0.25, 0.5))
    assert_first_order_meets_monte_carlo(idler_analysis)
    done = dataclasses.replace(idler_result, tolerance=idler_analysis)
    report = done.to_json()
    json.dumps(report, allow_nan=False)
    assert [d["name"] for d in report["tolerance"]["dimensions"]] == list(IDLER_DIMENSION_NAMES)
    # the train as built misses the path by more than the path accuracy: every built one does too
    assert idler_result.verification.max_error_mm > report["tolerance"]["path_accuracy_mm"]
    assert report["tolerance"]["violation_fraction"] == {"path accuracy": 1.0}


def test_idler_train_tolerances_name_its_own_dimensions():
    data = tomllib.loads(RICE.read_text())
    data["train"] = {"topology": "sun-idler-planet"}
    data["tolerances"] = {"phase_first_intermediate": 0.2}
    with pytest.raises(ProblemError, match="tolerances.phase_first_intermediate = 0.2: expected a dimension name"):
        reverse.parse_problem(data, "idler")


def test_path_accuracy_counts_the_built_tips_that_stray_further_than_asked(result, model):
    """A built tip moved off the designed one by just under and just over the accuracy somewhere on the turn
    passes and fails; a mechanism that does not close fails; the nominal mechanism passes."""
    condition = model.conditions
    accuracy = condition.tolerance_mm
    nominal = model.sampled(model.nominal[None])[0]
    moved = np.repeat(nominal[None], 4, axis=0)
    turn = model.whole_turn.start + 17
    moved[1, 0, turn] += 0.99 * accuracy
    moved[2, 1, turn] -= 1.01 * accuracy
    moved[3, :, turn] = np.nan
    flags = condition(moved, np.repeat(model.nominal[None], 4, axis=0))["path accuracy"]
    assert flags.tolist() == [False, False, True, True]


def test_path_accuracy_is_read_from_the_tolerances_table(rice_result):
    """The rice hoe's train (a tolerances table changes no dimension) analysed as the synthesis's last step analyses
    it, with a wide and a narrow path accuracy in its table."""
    data = tomllib.loads(RICE.read_text())
    data["tolerances"] = {"path_accuracy_mm": 40.0, "samples": 500}
    wide = analysed(dataclasses.replace(rice_result, problem=reverse.parse_problem(data, "rice")))
    assert wide.tolerance.monte_carlo.violation_fraction == {"path accuracy": 0.0}
    assert wide.to_json()["tolerance"]["path_accuracy_mm"] == 40.0
    assert "a built tip within 40 mm (15.7 % of the reach s + l)" in wide.to_markdown()
    data["tolerances"]["path_accuracy_mm"] = 1e-6
    narrow = analysed(dataclasses.replace(rice_result, problem=reverse.parse_problem(data, "rice")))
    assert narrow.tolerance.monte_carlo.violation_fraction == {"path accuracy": 1.0}
    assert not narrow.failures                    # the synthesis's own round trip still judges the design


@pytest.mark.parametrize("value", [0.0, -1.0, float("nan"), "2"])
def test_a_bad_path_accuracy_is_refused_naming_the_field(value):
    data = tomllib.loads(RICE.read_text())
    data["tolerances"] = {"path_accuracy_mm": value}
    with pytest.raises(ProblemError, match="tolerances.path_accuracy_mm = .*: expected a finite distance > 0"):
        reverse.parse_problem(data, "rice")

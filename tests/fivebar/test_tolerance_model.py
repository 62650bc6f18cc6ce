"""The built five-bar as a function of its manufactured dimensions (``fivebar.tolerance_model``) and the main
job's tolerance analysis: the model at its nominal dimensions is the verified mechanism, its exact Jacobian
equals central differences of the forward simulation, the gears' phases move rho as the designed motion says,
a planted change moves the key poses by J delta to second order, and first order meets the Monte Carlo at the
default tolerances and parts from it at ten times those."""
import dataclasses
import json

import numpy as np
import pytest

from tests.tolerance.model_checks import (
    assert_first_order_meets_monte_carlo,
    assert_jacobian_is_central_differences,
    assert_planted_change_is_second_order,
)
from transplanter.fivebar.loop_closure import close_loop
from transplanter.fivebar.tolerance_model import DIMENSION_NAMES, TURN_SAMPLES
from transplanter.fivebar.verification import TURN_SAMPLES as VERIFIED_SAMPLES
from transplanter.tolerance import analyse
from transplanter.tolerance.iso286 import clearance_um

pytestmark = pytest.mark.filterwarnings("error")      # a numpy warning is a failure


@pytest.fixture(scope="module")
def analysis(example_result):
    return example_result.tolerance


@pytest.fixture(scope="module")
def model(analysis):
    return analysis.model


def _turns(model):
    return np.radians(model.turns_deg)


def _close(mech, turns, rho):
    state = close_loop(mech, turns, rho)
    return np.vstack([state["p"].T, state["direction"]])


def test_nominal_built_mechanism_is_the_verified_one(example_result, model):
    motion = model.evaluate(model.nominal)
    problem, check = example_result.problem, example_result.verification
    k = len(problem.labels)
    reach = float(np.linalg.norm(problem.poses[:, :2], axis=1).max())
    assert np.abs(motion[:2, :k].T - problem.poses[:, :2]).max() < check.tolerance_mm
    assert np.abs(np.angle(np.exp(1j * (motion[2, :k] - problem.poses[:, 2])))).max() < check.tolerance_mm / reach
    step = VERIFIED_SAMPLES // TURN_SAMPLES
    assert np.abs(motion[:2, model.whole_turn].T - check.trajectory[::step]).max() < check.tolerance_mm
    assert model.names == DIMENSION_NAMES


def test_numpy_and_casadi_motions_agree(model, rng):
    dimensions = model.nominal + model.tolerances * rng.uniform(-1, 1, (4, len(model.nominal)))
    sampled = model.sampled(dimensions)
    for row, motion in zip(dimensions, sampled, strict=True):
        assert np.allclose(model.evaluate(row), motion, rtol=1e-12, atol=1e-10)


def test_sensitivities_equal_central_differences_of_the_forward_simulation(analysis):
    assert_jacobian_is_central_differences(analysis)


@pytest.mark.parametrize("name", ["rod_length_AF", "receiving_plate_length_BE", "clearance_B_x", "clearance_E_y"])
def test_linkage_sensitivities_equal_differences_of_the_verification_closure(example_result, analysis, model, name):
    """The same derivative from the verification's own route (``close_loop``, the design's rho), a mechanism
    rebuilt with the dimension moved."""
    mech, relative = example_result.design.mech, example_result.design.relative_angle
    turns = _turns(model)
    rho = relative.evaluate(turns)
    h = 1e-3

    def moved(delta):
        if name == "rod_length_AF":
            return dataclasses.replace(mech, rod_length=mech.rod_length + delta)
        if name == "receiving_plate_length_BE":
            return dataclasses.replace(mech, receiving_length=mech.receiving_length + delta)
        shift = np.array([delta, 0.0] if name.endswith("_x") else [0.0, delta])
        return dataclasses.replace(mech, hinge_b=mech.hinge_b + shift)

    difference = (_close(moved(h), turns, rho) - _close(moved(-h), turns, rho)) / (2 * h)
    exact = analysis.jacobian[:3, :, model.names.index(name)]
    assert np.abs(exact - difference).max() <= 1e-6 * np.abs(exact).max()


def test_gear_phases_move_rho_as_the_designed_motion_says(example_result, model):
    """The planet's phase adds to rho exactly; the sun's shifts the carrier turn the train sees, rho1 + chi(c +
    phase), which the model's second-order expansion of the gears' motion meets to third order in the phase."""
    mech, relative = example_result.design.mech, example_result.design.relative_angle
    turns, tolerance_mm = _turns(model), example_result.verification.tolerance_mm

    def miss(name, phase, rho):
        dimensions = model.nominal.copy()
        dimensions[model.names.index(name)] = phase
        return np.abs(model.sampled(dimensions[None])[0][:2] - _close(mech, turns, rho)[:2]).max()

    assert miss("phase_planet", 0.1, relative.evaluate(turns) + np.radians(0.1)) < tolerance_mm
    sun = [miss("phase_sun", phase, relative.evaluate(turns + np.radians(phase))) for phase in (0.1, 0.05)]
    assert sun[0] < 10 * tolerance_mm                    # at the default phase tolerance: 1e-6 of a mm
    assert 6 < sun[0] / sun[1] < 10                      # the miss is of third order in the phase


def test_planted_change_moves_the_key_poses_by_j_delta_to_second_order(analysis):
    assert_planted_change_is_second_order(analysis, "carrier_length_OA", (0.05, 0.1))


def test_first_order_meets_the_monte_carlo_at_the_default_tolerances(analysis):
    assert_first_order_meets_monte_carlo(analysis)


def test_ten_times_the_tolerances_part_first_order_from_the_monte_carlo(model):
    wide = analyse(model, {d.name: 10 * d.tolerance for d in model.dimensions})
    position, angle = wide.disagreement()
    assert np.any(np.r_[position, angle] > 0.10)
    section = wide.to_json()
    assert not all(pose["first_order_holds"] for pose in section["key_poses"])
    assert "First order breaks" in "\n".join(wide.to_markdown())


def test_report_section(example_result, analysis, model):
    report = example_result.to_json()
    section = report["tolerance"]
    json.dumps(report, allow_nan=False)
    assert [d["name"] for d in section["dimensions"]] == list(DIMENSION_NAMES)
    design_table = report["design"]
    for d in section["dimensions"]:
        if d["name"] in design_table:
            assert d["nominal"] == pytest.approx(design_table[d["name"]], rel=1e-12)
    labels = example_result.problem.labels
    assert [p["label"] for p in section["key_poses"]] == list(labels)
    j = model.names.index("rod_length_AF")
    assert section["sensitivity"]["rod_length_AF"][labels[1]] == pytest.approx(
        [analysis.jacobian[0, 1, j], analysis.jacobian[1, 1, j], np.degrees(analysis.jacobian[2, 1, j])])
    assert set(section["violation_fraction"]) >= {"closure margin", "return tolerance", "ranges.ep"}
    assert len(section["largest_contributions"]) == 3
    allocation = section["allocation"]
    assert max(allocation["first_order_3sigma_mm"]) <= section["allocation"]["pose_position_mm"] * (1 + 1e-6)
    markdown = example_result.to_markdown()
    assert "## Tolerances (the built mechanism)" in markdown and "Dimensions that matter most" in markdown
    assert {"tolerance_trajectory", "tolerance_band", "tolerance_contributions"} <= set(example_result.draw_figures())


def test_hinge_plays_come_from_an_h7_g6_fit_on_the_drawings_shafts(example_result, model):
    """O turns on the sun's fixed shaft, A on the planet's, F, E and B on the hinge pins: each hinge's play is
    half the largest clearance of an H7/g6 fit on that diameter, and the report's dimension table says so."""
    shafts = example_result.shafts.shafts
    dimensions = {d.name: d for d in model.dimensions}
    markdown = example_result.to_markdown()
    for hinge, shaft in (("O", "sun"), ("A", "planet"), ("F", "hinge"), ("E", "hinge"), ("B", "hinge")):
        diameter = shafts[shaft].diameter
        lower, upper = clearance_um(diameter)
        for axis in "xy":
            play = dimensions[f"clearance_{hinge}_{axis}"]
            assert play.tolerance == pytest.approx(upper / 2000, rel=1e-12) and lower >= 0
            assert play.what == f"radial play, H7/g6 on {diameter:g} mm"
        row = f"| clearance_{hinge}_x | 0 | {upper / 2000:.4g} | mm | radial play, H7/g6 on {diameter:g} mm |"
        assert row in markdown

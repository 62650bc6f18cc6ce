"""The five-bar's verification closes the loop by its own route (Wang et al. 2025 eq 8-9, by Newton) and reports
a mechanism built wrong."""
import dataclasses

import numpy as np
import pytest

from transplanter.fivebar.loop_closure import close_loop
from transplanter.fivebar.verification import verify
from transplanter.trains.planetary import design_train

TURN = np.linspace(0, 2 * np.pi, 3600, endpoint=False)


@pytest.fixture(scope="module")
def result(example_result):
    return example_result


def _wrapped(angle):
    return np.angle(np.exp(1j * angle))


@pytest.mark.parametrize("flip", [1.0, -1.0])
def test_newton_closure_agrees_with_circle_intersection_over_a_turn(result, flip):
    """Both assembly branches: the eq (9) start picks the branch the circle intersection takes."""
    mech = dataclasses.replace(result.design.mech, branch=flip * result.design.mech.branch)
    rho = result.design.relative_angle.evaluate(TURN)
    newton, circles = close_loop(mech, TURN, rho), mech.forward(TURN, rho)
    assert not np.isnan(newton["p"]).any()
    for point in ("e", "p"):
        assert np.abs(newton[point] - circles[point]).max() < 1e-9
    assert np.abs(_wrapped(newton["direction"] - circles["direction"])).max() < 1e-11
    assert np.abs(newton["margin"] - circles["margin"]).max() < 1e-12
    assert newton["residual"].max() < 1e-13
    # E really is on the other branch: the flip moves it far from the design's E
    if flip < 0:
        assert np.linalg.norm(newton["e"] - close_loop(result.design.mech, TURN, rho)["e"], axis=1).min() > 1.0


def test_a_chain_that_cannot_close_is_nan_where_eq_10_is_negative(result):
    """Shorten B-E until the chain jams over part of the turn: the closure says where, as eq (10) does."""
    mech = dataclasses.replace(result.design.mech, receiving_length=0.8 * result.design.mech.receiving_length)
    rho = result.design.relative_angle.evaluate(TURN)
    newton, circles = close_loop(mech, TURN, rho), mech.forward(TURN, rho)
    jammed = newton["margin"] < 0
    assert 0 < jammed.sum() < len(TURN)
    assert np.array_equal(np.isnan(newton["p"][:, 0]), jammed)
    assert np.array_equal(jammed, np.isnan(circles["p"][:, 0]))


def test_the_designed_mechanism_passes(result):
    check = result.verification
    assert check.passed, check.failures
    assert check.key_position_errors_mm.max() <= check.tolerance_mm
    assert 0 < check.tolerance_mm < 1e-5


def _verify(result, mech=None, train=None):
    design = result.design
    return verify(result.problem, mech or design.mech, design.relative_angle, train or result.train,
                  design.stroke.carrier_turns)


@pytest.mark.parametrize("stage", [0, 1])
def test_a_gear_stage_at_the_wrong_center_distance_is_reported(result, stage):
    """0.5 % on one centre distance changes that stage's ratio (the driven curve is a - r1): caught."""
    distances = list(result.train.center_distances)
    distances[stage] *= 1.005
    check = _verify(result, train=dataclasses.replace(result.train, center_distances=tuple(distances)))
    assert not check.passed
    assert check.key_position_errors_mm[1:].min() > 1e4 * check.tolerance_mm
    assert sum("key pose" in failure for failure in check.failures) >= 6


def test_gears_cut_for_another_relative_angle_are_reported(result):
    relative = result.design.relative_angle
    wrong = design_train(dataclasses.replace(relative, coefficients=1.005 * relative.coefficients),
                         result.train.center_distances)
    check = _verify(result, train=wrong)
    assert not check.passed and check.roundtrip_max_error_mm > 1e4 * check.tolerance_mm


@pytest.mark.parametrize("field", ["rod_length", "receiving_length", "carrier_length"])
def test_a_link_a_tenth_of_a_millimetre_off_is_reported(result, field):
    mech = result.design.mech
    check = _verify(result, mech=dataclasses.replace(mech, **{field: getattr(mech, field) + 0.1}))
    assert not check.passed
    assert check.key_position_errors_mm.max() > 1e4 * check.tolerance_mm
    assert any(failure.startswith("key pose P") and "mm (tolerance" in failure for failure in check.failures)

"""The derived curvature of the train's four pitch curves against the gear library's own curves."""
import numpy as np
import pytest

from transplanter._generated.train_pitch_curvature import train_pitch_curvature
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.generated import numpy_twin
from transplanter.geometry.periodic_bspline import basis_matrix, evaluate, knots
from transplanter.trains.planetary import design_train

curvature = numpy_twin(train_pitch_curvature)


def _derived(relative: RelativeAngle, c: np.ndarray, k: float):
    slope = [relative.evaluate(c, order) for order in (1, 2, 3)]
    return curvature(slope, [np.full_like(c, k)])


def test_a_constant_ratio_gives_four_circles_of_half_the_center_distance():
    """rho' = 1, k = 1: every gear is a circle of radius a / 2
    (a kappa = 2, rho / a = 1/2, convexity r^2 / a^2 = 1/4)."""
    convexity, bend, radius = curvature([[1.0], [0.0], [0.0]], [[1.0]])
    assert np.allclose(convexity, 0.25, rtol=1e-15) and np.allclose(bend, 2.0, rtol=1e-15)
    assert np.allclose(radius, 0.5, rtol=1e-15)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_derived_curvature_is_the_gear_library_curvature_of_the_designed_train(seed):
    """Ground truth: ``design_train`` builds the four curves (conjugates through the gear-pair library);
    their convexity / a^2 and curvature radius / a at each contact equal the derived ones at that carrier turn,
    whatever a1 and a2 (the center distance cancels)."""
    rng = np.random.default_rng(seed)
    relative = RelativeAngle(0.4, np.r_[0.0, rng.normal(0, 0.12, 11)])
    centers = tuple(rng.uniform(15.0, 40.0, 2))
    train = design_train(relative, centers)
    k = train.correction
    sun_turns = train.stage_one.phi1
    # wrapped as the library wraps
    intermediate_turns = train.intermediate_turn.inverse(np.mod(train.stage_two.phi1, 2 * np.pi))
    convex, _, radius = _derived(relative, sun_turns, k)
    convex2, _, radius2 = _derived(relative, intermediate_turns, k)
    stages = ((train.stage_one, convex[:2], radius[:2]), (train.stage_two, convex2[2:], radius2[2:]))
    signs = []
    for stage, derived_convexity, derived_radius in stages:
        a = stage.center_distance
        for side in range(2):
            library = stage.convexity[side] / a**2
            assert np.abs(derived_convexity[side] - library).max() <= 1e-9 * np.abs(library).max()
            finite = np.abs(stage.curvature_radius[side]) < 1e3 * a     # away from inflections
            assert np.allclose(derived_radius[side][finite] * a, stage.curvature_radius[side][finite], rtol=1e-8)
            signs.append(np.sign(library))
    assert {-1.0, 1.0} <= set(np.concatenate(signs)), "convex and concave stretches alike are compared"


def test_third_derivative_rows_are_right_continuous_at_the_knots(rng):
    """The curvature rows use rho'''; at a knot the basis gives the right-hand value, like ``evaluate``."""
    q = rng.normal(size=12)
    x = np.r_[knots(12), knots(12) + 1e-12]
    assert np.abs(basis_matrix(x, 12, 3) @ q - evaluate(x, q, 3)).max() < 1e-12

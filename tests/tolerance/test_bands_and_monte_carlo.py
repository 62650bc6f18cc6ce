"""First-order bands, shares and the Monte Carlo on a mechanism whose motion is linear in its dimensions, where
first order is exact and the variances, bands and violation fractions have closed forms."""
import numpy as np
import pytest

from tests.tolerance.linear_model import linear_model
from transplanter.tolerance import ToleranceSettings, analyse
from transplanter.tolerance.bands import largest_eigenvalue, worst_case_bands
from transplanter.tolerance.monte_carlo import draw

MATRIX = np.array([[1.0, 0.0, 2.0], [0.0, 3.0, 0.0], [0.01, 0.0, 0.0]])
TOLERANCES = [0.1, 0.2, 0.05]


def test_largest_eigenvalue_matches_numpy(rng):
    a = rng.normal(size=(20, 2, 2))
    covariance = a @ np.swapaxes(a, -1, -2)
    assert np.allclose(largest_eigenvalue(covariance), np.linalg.eigvalsh(covariance)[:, -1], rtol=1e-12)


@pytest.mark.parametrize("distribution, sigma_factor", [("uniform", 1 / np.sqrt(3)), ("normal", 1 / 3)])
def test_first_order_band_is_the_covariance_of_the_linear_motion(distribution, sigma_factor):
    model = linear_model(MATRIX, TOLERANCES)
    analysis = analyse(model, ToleranceSettings(distribution=distribution, samples=20000))
    sigma = np.array(TOLERANCES) * sigma_factor
    covariance = (MATRIX[:2] * sigma**2) @ MATRIX[:2].T
    assert analysis.first_order_3sigma_mm[0] == pytest.approx(3 * np.sqrt(np.linalg.eigvalsh(covariance)[-1]), 1e-12)
    assert analysis.first_order_3sigma_deg[0] == pytest.approx(np.degrees(3 * 0.01 * sigma[0]), 1e-12)
    # the Monte Carlo of a linear motion agrees up to its sampling error (about 1 / sqrt(2 N) relative)
    assert analysis.monte_carlo.position_3sigma_mm[0] == pytest.approx(analysis.first_order_3sigma_mm[0], rel=0.03)
    shares = analysis.position_shares[0]
    expected = np.sum(MATRIX[:2] ** 2, axis=0) * sigma**2
    assert np.allclose(shares, expected / expected.sum(), rtol=1e-12)
    assert analysis.largest_contributions(1)[0][0] == "d1"


def test_worst_case_adds_every_limit():
    jacobian = MATRIX[:, None, :]
    position, angle = worst_case_bands(jacobian, np.array(TOLERANCES))
    assert position[0] == pytest.approx(0.1 * 1 + 0.2 * 3 + 0.05 * 2)
    assert angle[0] == pytest.approx(np.degrees(0.01 * 0.1))


def test_violation_fraction_is_the_probability_of_the_uniform_dimension_past_the_limit():
    # x = d0 alone, d0 uniform in [-0.1, 0.1]: P(x > 0.05) = 1/4
    model = linear_model(np.array([[1.0], [0.0], [0.0]]), [0.1], condition_limit=0.05)
    analysis = analyse(model, ToleranceSettings(samples=40000))
    assert analysis.monte_carlo.violation_fraction["x limit"] == pytest.approx(0.25, abs=0.01)


def test_samples_are_seeded_and_within_their_limits():
    model = linear_model(MATRIX, TOLERANCES)
    first, again = draw(model, 1000, 7, "uniform"), draw(model, 1000, 7, "uniform")
    assert np.array_equal(first, again)
    assert np.all(np.abs(first) <= TOLERANCES)
    assert not np.array_equal(first, draw(model, 1000, 8, "uniform"))

"""The tolerance allocation against its closed-form answer on a linear mechanism, and its own check."""
import numpy as np
import pytest

from tests.tolerance.linear_model import linear_model
from transplanter.tolerance import ToleranceSettings, analyse
from transplanter.tolerance.dimensions import ALLOCATION_RANGE


def test_allocation_loosens_each_dimension_to_the_required_band():
    # x = d0, y = d1: the covariance is diag(sigma0^2, sigma1^2), so 3 sigma <= r holds for both exactly when
    # each t_i <= r / (3 / sqrt(3)); the angle does not move. The loosest box puts both there.
    model = linear_model(np.array([[1.0, 0.0], [0.0, 1.0], [0.0, 0.0]]), [0.1, 0.1])
    required = 0.5
    analysis = analyse(model, ToleranceSettings(pose_position_mm=required))
    allocation = analysis.allocation
    assert allocation is not None
    assert np.allclose(allocation.tolerances, required / np.sqrt(3), rtol=1e-6)
    assert allocation.position_3sigma_mm[0] == pytest.approx(required, rel=1e-6)
    assert allocation.binding == ("pose_position_mm at K",)


def test_allocation_stops_at_the_loosest_allowed_tolerance():
    model = linear_model(np.array([[1.0, 0.0], [0.0, 0.0], [0.0, 0.0]]), [0.1, 0.1])
    allocation = analyse(model, ToleranceSettings(pose_position_mm=0.5)).allocation
    assert allocation is not None
    # d1 moves nothing: it goes to its largest; d0 to the band
    assert allocation.tolerances[1] == pytest.approx(0.1 * ALLOCATION_RANGE[1], rel=1e-6)
    assert allocation.tolerances[0] == pytest.approx(0.5 / np.sqrt(3), rel=1e-6)

"""The trajectory figure's band (``tolerance.figures``): its half-width along the path's normal is the 3-sigma
error ellipse's extent there, and the magnification it is drawn at is a stated 1-2-5 factor."""
import numpy as np
import pytest

from transplanter.tolerance.figures import DRAWN_BAND, band_normal_offsets, magnification


def test_a_circle_with_round_ellipses_has_radial_normals_and_a_band_of_three_sigma():
    turns = np.linspace(0, 2 * np.pi, 90, endpoint=False)
    path = 40 * np.c_[np.cos(turns), np.sin(turns)]
    covariance = np.repeat((0.2**2 * np.eye(2))[None], len(turns), axis=0)
    normal, width = band_normal_offsets(path, covariance, closed=True)
    assert np.abs(np.abs(np.sum(normal * path / 40, axis=1)) - 1).max() < 1e-12
    assert width == pytest.approx(np.full(len(turns), 0.6), rel=1e-12)


def test_a_straight_path_takes_the_ellipse_extent_across_it():
    """Along x, the band's half-width is 3 sqrt(C_yy), whatever C_xx and C_xy are (one-sided at the ends)."""
    path = np.c_[np.linspace(0, 10, 11), np.zeros(11)]
    covariance = np.repeat(np.array([[4.0, 0.5], [0.5, 0.09]])[None], 11, axis=0)
    normal, width = band_normal_offsets(path, covariance, closed=False)
    assert np.abs(np.abs(normal[:, 1]) - 1).max() < 1e-15
    assert width == pytest.approx(np.full(11, 0.9), rel=1e-12)


@pytest.mark.parametrize("band, extent, factor", [(1.0, 100.0, 5.0), (0.01, 100.0, 500.0), (0.3, 100.0, 10.0),
                                                  (6.0, 190.0, 1.0), (0.0, 100.0, 1.0)])
def testmagnification_is_the_largest_1_2_5_factor_that_keeps_the_band_small(band, extent, factor):
    assert magnification(band, extent) == factor
    assert factor == 1.0 or factor * band <= DRAWN_BAND * extent

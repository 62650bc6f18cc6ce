"""The driven pitch curve that rolls on a driver (``trains.rolling.conjugate_curve``), against a pair known in
closed form."""
import numpy as np

from transplanter.gears.pitch_curves import ellipse
from transplanter.trains.rolling import conjugate_curve


def test_conjugate_of_a_focal_ellipse_is_the_same_ellipse():
    """At a = 2 x semi-major axis the driven curve is the ellipse turned half a turn: r = p / (1 + e cos psi)."""
    curve = conjugate_curve(ellipse(30.0, 0.3), 60.0)
    psi = np.linspace(0, 2 * np.pi, 50)
    r, slope, _ = curve.evaluate(psi)
    p = 30 * (1 - 0.09)
    assert np.abs(r - p / (1 + 0.3 * np.cos(psi))).max() < 1e-10
    assert np.abs(slope - p * 0.3 * np.sin(psi) / (1 + 0.3 * np.cos(psi))**2).max() < 1e-8

"""The closure band: the relative angles at which the five-bar closes with at least a margin, from
the derived bounds on cos(BAF), against the independent forward kinematics (circle intersections)."""
import numpy as np
import pytest

from transplanter._generated.fivebar_closure_band import fivebar_closure_band
from transplanter.fivebar.candidate import GRID
from transplanter.fivebar.closure_band import closure_band, rod_side
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.generated import numpy_twin

MECH = FiveBar(48.0, -0.5, 246.0, np.array([-78.6, -30.1]), 186.0, np.array([99.4, -11.3]),
               np.array([35.0, -33.1]), -1.0)
#: A relative angle this five-bar follows with F on one side of AB, its margin falling below 0.01 in places.
PATH = RelativeAngle(-1.26, np.radians([0, 3, -4, 2, 0, 1, -2, 3, 0, -1, 2, 0])).evaluate(GRID)


@pytest.mark.parametrize("floor", [0.01, 0.05])
def test_the_band_is_where_the_forward_kinematics_gives_the_margin(floor):
    """The edges have the margin ``floor`` exactly, the middle more, just outside less; and a relative angle is in
    the band exactly where the forward kinematics gives it at least ``floor`` (both happen along the path)."""
    side = rod_side(MECH, GRID, PATH)
    assert np.all(side == side[0])
    low, high = closure_band(MECH, GRID, floor, side[0], PATH)
    margin = {name: MECH.forward(GRID, rho)["margin"]
              for name, rho in (("low", low), ("high", high), ("middle", (low + high) / 2), ("below", low - 1e-3),
                                ("above", high + 1e-3), ("path", PATH))}
    assert np.abs(margin["low"] - floor).max() < 1e-12 and np.abs(margin["high"] - floor).max() < 1e-12
    assert margin["middle"].min() > floor and margin["below"].max() < floor and margin["above"].max() < floor
    inside = (low <= PATH) & (high >= PATH)
    assert np.array_equal(inside, margin["path"] >= floor)
    assert 0 < inside.sum() < len(GRID)


def test_the_band_follows_the_side_of_line_ab():
    """On the other side of AB the band is the mirror image about the direction A -> B: the two bands' edges sum to
    twice that direction (as a relative angle, up to whole turns). Where the sides are apart (cos(BAF) = 1 and
    -1 both below the margin), F stays on the band's side; where they meet, the band crosses the line AB."""
    low, high = closure_band(MECH, GRID, 0.01, 1.0, PATH)
    other_low, other_high = closure_band(MECH, GRID, 0.01, -1.0, PATH)
    frame = MECH.hinge_b - MECH.carrier_point(GRID)
    toward_b = np.arctan2(frame[:, 1], frame[:, 0]) - MECH.carrier_angle + GRID
    assert np.abs(np.angle(np.exp(1j * (low + other_high - 2 * toward_b)))).max() < 1e-12
    assert np.abs(np.angle(np.exp(1j * (high + other_low - 2 * toward_b)))).max() < 1e-12
    lengths = [MECH.rod_length, MECH.link_length, MECH.receiving_length]
    k_low, k_high = numpy_twin(fivebar_closure_band)(lengths, np.hypot(frame[:, 0], frame[:, 1])[None], [0.01])[0]
    apart = (k_high < 1) & (k_low > -1)
    for side, band in ((1.0, (low, high)), (-1.0, (other_low, other_high))):
        for rho in (band[0] + 1e-9, (band[0] + band[1]) / 2, band[1] - 1e-9):
            assert np.all(rod_side(MECH, GRID[apart], rho[apart]) == side)
        edges = np.r_[rod_side(MECH, GRID[~apart], band[0][~apart] + 1e-9),
                      rod_side(MECH, GRID[~apart], band[1][~apart] - 1e-9)]
        assert set(edges) == {-1.0, 1.0}
    assert 0 < apart.sum() < len(GRID)

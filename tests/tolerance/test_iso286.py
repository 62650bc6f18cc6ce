"""ISO 286-1 H7/g6 limits (``tolerance.iso286``) against values of the standard's tables, the radial play a fit
gives, the nominal-size ranges' ends, and the refusal of sizes the tables do not cover."""
import pytest

from transplanter.errors import ProblemError
from transplanter.tolerance.dimensions import HINGE_PLAY_MM, hinge_plays
from transplanter.tolerance.iso286 import IT6_UM, IT7_UM, clearance_um, hole_h7_um, radial_play_mm, shaft_g6_um

#: nominal diameter (mm) -> H7 hole (EI, ES) and g6 shaft (ei, es), um, as ISO 286-2 lists them.
STANDARD = {10.0: ((0, 15), (-14, -5)), 25.0: ((0, 21), (-20, -7)), 50.0: ((0, 25), (-25, -9)),
            2.0: ((0, 10), (-8, -2)), 100.0: ((0, 35), (-34, -12)), 500.0: ((0, 63), (-60, -20))}


@pytest.mark.parametrize("diameter", sorted(STANDARD))
def test_limits_are_the_standard_ones(diameter):
    hole, shaft = STANDARD[diameter]
    assert hole_h7_um(diameter) == hole and shaft_g6_um(diameter) == shaft


def test_a_range_includes_its_upper_end_and_not_its_lower():
    assert shaft_g6_um(10.0) == (-14, -5)          # 6 < d <= 10
    assert shaft_g6_um(10.001) == (-17, -6)        # 10 < d <= 18
    assert hole_h7_um(10.001) == (0, 18)


def test_grades_grow_with_size_and_it7_is_wider_than_it6():
    assert list(IT6_UM) == sorted(IT6_UM) and list(IT7_UM) == sorted(IT7_UM)
    assert all(seven > six for six, seven in zip(IT6_UM, IT7_UM, strict=True))


def test_radial_play_is_half_the_largest_diametral_clearance():
    assert clearance_um(10.0) == (5, 29)            # 0 - (-5) and 15 - (-14)
    assert radial_play_mm(10.0) == pytest.approx(0.0145, abs=1e-15)


@pytest.mark.parametrize("diameter", [0.0, -5.0, 500.5, float("nan")])
def test_sizes_outside_the_tables_are_refused_naming_the_field(diameter):
    with pytest.raises(ProblemError, match="shafts.hinge_mm = .* mm: ISO 286 tables here cover H7/g6 fits on "
                                           "diameters above 0 and up to 500 mm"):
        radial_play_mm(diameter, "shafts.hinge_mm")


def test_hinge_plays_say_where_each_play_came_from():
    plays = {d.name: d for d in hinge_plays({"O": 25.0, "B": None})}
    assert plays["clearance_O_x"].tolerance == plays["clearance_O_y"].tolerance == pytest.approx(0.0205)
    assert plays["clearance_O_x"].what == "radial play, H7/g6 on 25 mm"
    assert plays["clearance_B_y"].tolerance == HINGE_PLAY_MM
    assert plays["clearance_B_y"].what == "radial play, no shaft diameter set"

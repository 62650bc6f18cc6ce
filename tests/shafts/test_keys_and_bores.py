"""Parallel keys to DIN 6885-1, the keyed bore's geometry, the default diameters and the rim check."""
import numpy as np
import pytest
import shapely

from transplanter.errors import ProblemError
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.keys import DIN_6885, STANDARD_DIAMETERS, parallel_key
from transplanter.shafts.sizing import (
    GEAR_SIZE_FRACTION,
    PIN_BEARING_PRESSURE_MPA,
    PIN_SHEAR_STRESS_MPA,
    TORSION_STRESS_MPA,
    diameter_for_gear,
    diameter_for_pin,
    diameter_for_torque,
    min_rim,
    rim_failures,
)
from transplanter.solids.sizes import PLATE_THICKNESS_PIN_DIAMETERS


def test_table_ranges_follow_on_and_keys_grow_with_the_shaft():
    ranges = [span for span, _ in DIN_6885]
    assert all(previous[1] == current[0] for previous, current in zip(ranges, ranges[1:], strict=False))
    widths = [key.width for _, key in DIN_6885]
    assert widths == sorted(widths)
    assert all(key.hub_depth < key.shaft_depth < key.height + 1e-12 for _, key in DIN_6885)


def test_key_by_diameter_at_the_range_edges():
    assert parallel_key(22).width == 6      # up to and including 22
    assert parallel_key(22.001).width == 8
    assert parallel_key(30).hub_depth == 3.3
    with pytest.raises(ProblemError, match=r"shafts\.planet_mm: 5 mm has no parallel key"):
        parallel_key(5, "shafts.planet_mm")


def test_keyed_bore_outline_has_the_area_of_disk_and_keyway():
    bore = KeyedBore.for_shaft(20.0, direction=0.7)
    r, half, alpha = bore.radius, bore.key.width / 2, bore.half_angle
    # the disk, less its segment beyond the keyway's chord, plus the keyway's rectangle from that chord out
    chord = r * np.cos(alpha)
    expected = np.pi * r**2 - r**2 * (alpha - np.sin(alpha) * np.cos(alpha)) + 2 * half * (bore.reach - chord)
    polygon = shapely.Polygon(bore.outline())
    assert polygon.is_valid
    assert polygon.area == pytest.approx(expected, rel=1e-4)
    # the keyway's bottom lies on the keyway's direction at d/2 + t2
    far = bore.outline()[np.argmax(bore.outline() @ [np.cos(0.7), np.sin(0.7)])]
    assert far @ [np.cos(0.7), np.sin(0.7)] == pytest.approx(bore.reach, abs=1e-12)
    assert bore.reach == pytest.approx(10.0 + 2.8)


@pytest.mark.parametrize("torque_nm", [0.5, 3.0, 40.0, 700.0])
def test_torque_diameter_is_the_smallest_standard_one_within_the_stress(torque_nm):
    def stress(d):
        return 16 * torque_nm * 1e3 / (np.pi * d**3)

    d = diameter_for_torque(torque_nm)
    assert stress(d) <= TORSION_STRESS_MPA
    smaller = [s for s in STANDARD_DIAMETERS if s < d]
    assert not smaller or stress(smaller[-1]) > TORSION_STRESS_MPA


@pytest.mark.parametrize(("force_n", "thickness_mm"), [(50.0, None), (2500.0, None), (9000.0, None), (2500.0, 4.0),
                                                       (2500.0, 30.0)])
def test_pin_diameter_is_the_smallest_standard_one_within_shear_and_bearing(force_n, thickness_mm):
    def within(d):
        t = PLATE_THICKNESS_PIN_DIAMETERS * d if thickness_mm is None else thickness_mm
        return (force_n / (np.pi * d**2 / 4) <= PIN_SHEAR_STRESS_MPA
                and force_n / (d * t) <= PIN_BEARING_PRESSURE_MPA)

    d = diameter_for_pin(force_n, thickness_mm)
    assert within(d)
    smaller = [s for s in STANDARD_DIAMETERS if s < d]
    assert not smaller or not within(smaller[-1])


def test_a_thinner_plate_asks_a_thicker_pin():
    assert diameter_for_pin(2500.0, 4.0) > diameter_for_pin(2500.0, 30.0)


def test_gear_size_diameter_is_the_largest_standard_one_within_the_fraction():
    d = diameter_for_gear(40.0)
    assert d == 32 and d <= GEAR_SIZE_FRACTION * 40.0 < 35


def test_rim_check_fails_with_the_numbers_only_when_the_keyway_comes_too_close():
    bore = KeyedBore.for_shaft(30.0)            # key 8 x 7, t2 3.3: the keyway reaches 18.3 mm
    module = 2.0
    assert min_rim(module) == pytest.approx(1.2 * 2.25 * 2.0)
    assert rim_failures("sun", 18.3 + min_rim(module) + 1e-9, bore, module) == []
    (failure,) = rim_failures("sun", 20.0, bore, module)
    assert "18.300" in failure and "1.700" in failure and "5.400" in failure and "sun" in failure

"""Axis labels of the study's figures carry the unit the field's or quantity's name gives."""
import pytest

from transplanter.study.figures import axis_label


@pytest.mark.parametrize("path, unit", [
    ("key_poses.1.angle_deg", "deg"), ("key_poses.3.x", "mm"), ("gear_pressure_angle_max_deg.0", "deg"),
    ("design.carrier_length_OA", "mm"), ("ratio_range.1", "1"), ("roundtrip_max_error_mm", "mm"),
])
def test_the_unit_follows_the_name_an_array_entry_its_arrays(path, unit):
    assert axis_label(path) == f"{path} ({unit})"

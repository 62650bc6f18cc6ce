"""The reverse train moves with its path: the path turned about the carrier axis, the pivot and the path moved
together, and every length scaled (the path, the module) give the same arm, touches and total ratio range to 1e-9
relative, and the same gears (radius ranges, perimeters, teeth) to 1e-9 relative: next to a touch the pitch curves
take the arm's rates from the factored elbow (``reverse.touch_rates``), which has no 0 / 0 (with the rates averaged
``arm_inverse.TOUCH_LIMIT`` either side of a touch, the radii moved by 1e-6 between frames). The total ratio's range
is the extreme of the function, not of a grid (``reverse.ratio_extremes``): sampled, its value at a touch carried
the rates' rounding there (4e-6 relative between frames), ``TOUCH_ROUNDING``."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import Phase, given, settings
from hypothesis import strategies as st

from transplanter import reverse
from transplanter.reverse.arm_inverse import TOUCH_LIMIT
from transplanter.toml_fields import read_toml
from transplanter.trains.toothed_train import MODULE_RANGE

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "rice_hoe_reverse.toml"
#: The rounding error of the rates sampled TOUCH_LIMIT from a touch, relative to their size.
TOUCH_ROUNDING = np.finfo(float).eps / TOUCH_LIMIT**2


def _moved(data: dict, angle: float, shift, scale: float) -> dict:
    """The problem with its path turned by ``angle`` (rad) about the pivot and scaled about it by ``scale``, then
    path and pivot moved by ``shift``; the module scaled alike."""
    data = json.loads(json.dumps(data))
    pivot = np.asarray(data["arm"].get("pivot", [0.0, 0.0]), float)
    c, s = np.cos(angle), np.sin(angle)
    points = np.asarray(data["trajectory"]["points"], float) - pivot
    turned = scale * points @ np.array([[c, s], [-s, c]])
    data["trajectory"]["points"] = (turned + pivot + shift).tolist()
    data["arm"]["pivot"] = (pivot + shift).tolist()
    data["train"]["module"] *= scale
    return data


def _train(report: dict, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """What must not change, read from a train's report: the arm (lengths per scale, touches as points on the unit
    circle of u, so u = 1 and u = 0 agree; the ratio range) and the gears (radius ranges and perimeters per scale,
    teeth at the module)."""
    touches = np.exp(2j * np.pi * np.sort([touch["u"] for touch in report["touches"]])).view(float)
    arm = [report["carrier_length"] / scale, report["arm_length"] / scale, *touches, *report["ratio_range"]]
    gears = [[*np.divide(gear["radius_range_mm"], scale), gear["perimeter_mm"] / scale, gear["teeth_at_module"]]
             for gear in report["gears"]]
    return np.array(arm), np.array(gears)


@pytest.fixture(scope="module")
def example(rice_result):
    """The example's problem and what must not change, read from its train synthesised once per test process."""
    return read_toml(EXAMPLE), _train(rice_result.to_json())


#: Scales that keep the example's module among the modules teeth are cut at (``trains.toothed_train.MODULE_RANGE``):
#: beyond them the module is refused, the train keeps its pitch curves on a straight carrier, another design.
SCALES = tuple(limit / read_toml(EXAMPLE)["train"]["module"] for limit in MODULE_RANGE)


@settings(max_examples=3, deadline=None, phases=[Phase.explicit, Phase.generate])
@given(angle=st.floats(-np.pi, np.pi), shift=st.tuples(st.floats(-1e4, 1e4), st.floats(-1e4, 1e4)),
       scale=st.floats(*SCALES))
def test_the_train_moves_with_its_path(example, angle, shift, scale):
    data, (arm, gears) = example
    moved = reverse.synthesize(reverse.parse_problem(_moved(data, angle, shift, scale)), tolerance=False)
    moved_arm, moved_gears = _train(moved.to_json(), scale)
    np.testing.assert_allclose(moved_arm, arm, rtol=1e-9, atol=1e-12)   # atol: a zero
    np.testing.assert_allclose(moved_gears, gears, rtol=1e-9)


def test_the_ratio_range_bounds_the_sampled_ratio(rice_result):
    """The range found holds every grid value of i0 away from the touches, and comes within the touches' rounding
    (TOUCH_ROUNDING) of the extremes sampled at the touches, which are the rice path's extremes (at its inner touch
    the ratio bends sharply: a polynomial across the touch missed it by 1.6e-5)."""
    from transplanter.geometry.planar import TWO_PI
    from transplanter.reverse.ratio_extremes import TOUCH_REACH, ratio_range

    motion = rice_result.motion
    low, high = ratio_range(motion)
    ratio = motion.total_ratio()
    away = np.all([np.abs(np.mod(motion.grid - touch.parameter + np.pi, TWO_PI) - np.pi) > TOUCH_REACH
                   for touch in motion.touches], axis=0)
    assert low <= ratio[away].min() and ratio[away].max() <= high
    at_touches = ratio[~away]
    assert low == pytest.approx(at_touches.min(), rel=TOUCH_ROUNDING)
    assert high == pytest.approx(at_touches.max(), rel=TOUCH_ROUNDING)

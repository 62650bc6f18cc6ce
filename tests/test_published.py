"""Seed 000's published design (Table 4) against the exact 4-pose solution set of Table 1.

Table 4 gives the frame hinge B = (-78.83, -33.37) mm and the receiving plate BE = 227.68 mm;
Table 2 bounds the push plate EP to [55, 100] mm and Table 4 gives 55.01 mm. An exact 2R
chain B-E for the four key poses has B on the center-point curve. The published B is near
the curve but not on it, and the exact dyad with the published length |BE| has its B about
1.6 mm from the published one: the published design meets the poses to about a millimetre.
"""
import numpy as np
import pytest

from transplanter.problem import load_problem
from transplanter.synthesis import synthesize
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PUBLISHED_B = np.array([-78.83, -33.37])
PUBLISHED_BE = 227.68
PUBLISHED_EP = 55.01


@pytest.fixture(scope="module")
def family():
    problem = load_problem(ROOT / "examples/burmester_4poses.toml")
    result = synthesize(problem)
    return problem, result.dyads


def test_published_hinge_is_near_but_off_the_center_point_curve(family):
    _, dyads = family
    centers = np.array([d.center for d in dyads])
    gap = np.linalg.norm(centers - PUBLISHED_B, axis=1).min()
    assert 0.1 < gap < 1.0   # measured: 0.31 mm


def test_exact_dyad_with_the_published_length(family):
    problem, dyads = family
    near = [d for d in dyads if np.linalg.norm(d.center - PUBLISHED_B) < 5]
    lengths = np.array([d.length for d in near])
    k = np.flatnonzero(np.diff(np.sign(lengths - PUBLISHED_BE)))[0]
    w = (PUBLISHED_BE - lengths[k]) / (lengths[k + 1] - lengths[k])
    center = (1 - w) * near[k].center + w * near[k + 1].center
    circle = (1 - w) * near[k].circle + w * near[k + 1].circle
    b_shift = np.linalg.norm(center - PUBLISHED_B)
    ep = np.linalg.norm(circle - problem.poses[0, :2])
    assert 0.5 < b_shift < 3.0           # measured: 1.6 mm
    assert abs(ep - PUBLISHED_EP) < 3.0  # measured: 56.5 mm against 55.01

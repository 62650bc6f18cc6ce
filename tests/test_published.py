"""Wang et al. 2025's published design (Table 4) against the exact 4-pose solution set of Table 1.

Table 4 gives the frame hinge B = (-78.83, -33.37) mm and the receiving plate BE = 227.68 mm;
Table 2 bounds the push plate EP to [55, 100] mm and Table 4 gives 55.01 mm. An exact 2R
chain B-E for the four key poses has B on the center-point curve. The published B is near
the curve but not on it, and the exact dyad with the published length |BE| has its B about
1.6 mm from the published one: the published design meets the poses to about a millimetre.
"""
import numpy as np
import pytest

from transplanter.geometry.dyad import verify_dyad
from transplanter.burmester.problem import load_problem
from transplanter.burmester.synthesis import synthesize
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


def test_published_carrier_chain_meets_the_relative_poses():
    """Table 4: carrier OA = 47.47 mm at -28.59 deg, rod I AF = 275.88 mm at -100.88 deg (pose 1).

    Seen from the carrier (phases 0, -18, -50, -90 deg), A-F is a dyad through the four key
    poses. Its length changes by at most 0.088 mm over them (forward kinematics), and A lies
    0.18 mm from the exact center-point curve: close, not exact.
    """
    problem = load_problem(ROOT / "examples/burmester_relative.toml")
    a = 47.47 * np.array([np.cos(np.radians(-28.59)), np.sin(np.radians(-28.59))])
    f = a + 275.88 * np.array([np.cos(np.radians(-100.88)), np.sin(np.radians(-100.88))])
    published = verify_dyad(problem.poses, a, f, problem.link)
    assert 0.01 < published.max_residual_mm < 0.2
    centers = np.array([d.center for d in synthesize(problem).dyads])
    assert 0.05 < np.linalg.norm(centers - a, axis=1).min() < 0.5

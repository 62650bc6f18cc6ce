"""Ground truth: build a mechanism, take its poses, synthesise, recover it."""
import subprocess
import sys

import numpy as np
import pytest
from scipy.optimize import least_squares

from derivations.burmester import circular_cubic
from tests.burmester.ground_truth import dyad_poses, fourbar_poses
from transplanter.burmester.five_poses import center_cubic
from transplanter.burmester.four_poses import circle_cubic
from transplanter.burmester.problem import DyadProblem
from transplanter.burmester.synthesis import synthesize
from transplanter.geometry.dyad import Link, verify_dyad
from transplanter.geometry.poses import Frame, carry, relative_to_link, rotate_about, rotation


def _has_pair(dyads, center, circle, tol):
    return any(np.linalg.norm(d.center - center) < tol and np.linalg.norm(d.circle - circle) < tol for d in dyads)


def test_importing_the_burmester_solvers_builds_no_casadi_function():
    """The generated Functions are built on first use: a fresh interpreter that imports every
    Burmester solver has built none, and one 5-pose solve builds the three it needs."""
    script = ("import numpy as np; import transplanter.burmester.synthesis; "
              "from transplanter.generated import casadi_function as f; before = f.cache_info().currsize; "
              "from transplanter.burmester.five_poses import burmester_points; "
              "burmester_points(np.array([[0, 0, 0], [1, .2, .3], [1.8, .9, .5], [2.2, 1.9, .9], [2, 3, 1.4]])); "
              "print(before, f.cache_info().currsize)")
    counts = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, check=True).stdout.split()
    assert counts == ["0", "3"]


def test_three_poses_match_the_circumcircle(rng):
    """Circle point given: the center is the circumcenter of its three positions (built independently)."""
    poses, _, _ = dyad_poses(rng, 3, spread=50.0)
    circle = rng.normal(size=2) * 50
    a, b, c = carry(poses, circle)
    # circumcenter from the perpendicular bisectors
    matrix = 2 * np.array([b - a, c - a])
    center = np.linalg.solve(matrix, [b @ b - a @ a, c @ c - a @ a])
    result = synthesize(DyadProblem(poses, circle_points=circle[None], center_points=center[None]))
    assert np.allclose(result.dyads[0].center, center, atol=1e-9)
    assert np.allclose(result.dyads[1].circle, circle, atol=1e-9)  # the reverse problem comes back
    assert all(d.max_residual < 1e-12 for d in result.dyads)


@pytest.mark.parametrize("trial", range(6))
def test_four_poses_curves_contain_the_true_dyad(trial):
    rng = np.random.default_rng(trial)
    poses, center, circle = dyad_poses(rng, 4, spread=80.0)
    local = Frame.of(poses).local_poses(poses)
    frame = Frame.of(poses)
    assert abs(circular_cubic(center_cubic(local), *frame.to_local(center))) < 1e-9
    assert abs(circular_cubic(circle_cubic(local), *frame.to_local(circle))) < 1e-9
    radius = 3 * max(np.linalg.norm(frame.to_local(center)), np.linalg.norm(frame.to_local(circle)))
    result = synthesize(DyadProblem(poses, samples=2000, radius_mm=radius * frame.scale))
    assert len(result.dyads) > 100
    assert max(d.max_residual for d in result.dyads + result.circle_curve_dyads) < 1e-9
    # the family passes through the true center, and there its circle point is the true one
    centers = np.array([d.center for d in result.dyads])
    nearest = np.linalg.norm(centers - center, axis=1).argmin()
    assert np.linalg.norm(centers[nearest] - center) < 0.02 * frame.scale
    exact = synthesize(DyadProblem(poses[:3], center_points=center[None])).dyads[0]
    assert np.allclose(verify_dyad(poses, center, exact.circle).residuals_mm, 0, atol=1e-8)
    circles = np.array([d.circle for d in result.circle_curve_dyads])
    assert np.linalg.norm(circles - circle, axis=1).min() < 0.02 * frame.scale


def _multistart(poses, starts, rng):
    """Dense multistart Newton on eq (1), independent of the resultant: the reference set."""
    # ``carry(poses, z[2:])`` with the poses' rotations made once, not at each of the thousands of residuals (the
    # same einsum of the same matrices: the same bits)
    turns = rotation(poses[:, 2] - poses[0, 2])

    def residual(z):
        moving = poses[:, :2] + np.einsum("nij,...j->...ni", turns, np.asarray(z[2:], float) - poses[0, :2])
        d2 = np.sum((moving - z[:2]) ** 2, axis=1)
        return (d2[1:] - d2[0]) / 2

    def jacobian(z):
        """The residual's exact derivative: d2 = |m - c|^2 with m the moved circle point, so d d2/dc = -2 (m - c)
        and d d2/dz = 2 (m - c) R (the halves cancel the 2s); a finite-difference one (the default) costs two more
        residuals per row and per step, and the same 8 trials find the same points with either."""
        off = poses[:, :2] + np.einsum("nij,...j->...ni", turns, np.asarray(z[2:], float) - poses[0, :2]) - z[:2]
        rows = np.c_[-off, np.einsum("ni,nij->nj", off, turns)]
        return rows[1:] - rows[0]
    found = []
    for _ in range(starts):
        fit = least_squares(residual, rng.normal(size=4) * 3, jac=jacobian, method="lm", xtol=1e-15, ftol=1e-15,
                            gtol=1e-15)
        converged = np.abs(fit.fun).max() < 1e-11 and np.abs(fit.x).max() < 1e3
        if converged and all(np.linalg.norm(fit.x - f) > 1e-5 for f in found):
            found.append(fit.x)
    return found


@pytest.mark.parametrize("trial", range(8))
def test_five_poses_resultant_is_complete(trial):
    """The true pair is found, the count is 0, 2 or 4, and a 300-start multistart finds nothing more."""
    rng = np.random.default_rng(100 + trial)
    poses, center, circle = dyad_poses(rng, 5)
    result = synthesize(DyadProblem(poses))
    assert len(result.dyads) in (2, 4)
    assert _has_pair(result.dyads, center, circle, 1e-8)
    assert all(d.max_residual < 1e-10 for d in result.dyads)
    for z in _multistart(poses, 300, rng):
        assert _has_pair(result.dyads, z[:2], z[2:], 1e-6), f"multistart found {z} that the resultant missed"


def test_five_poses_of_a_fourbar_give_both_of_its_dyads():
    poses, truth = fourbar_poses(np.radians([10, 70, 130, 190, 250]))
    result = synthesize(DyadProblem(poses))
    for center, circle in truth:
        assert _has_pair(result.dyads, center, circle, 1e-8)


def test_five_poses_without_real_solutions_return_none(rng):
    """Counted over random poses, some have no real Burmester pair: none is invented for them."""
    counts = []
    for _ in range(60):
        poses = np.c_[rng.normal(size=(5, 2)), rng.uniform(-2, 2, 5)]
        dyads = synthesize(DyadProblem(poses)).dyads
        assert all(d.max_residual < 1e-10 for d in dyads)
        counts.append(len(dyads))
    assert set(counts) <= {0, 2, 4}
    assert 0 in counts and 4 in counts


def test_many_poses_recover_an_exact_fourbar():
    poses, truth = fourbar_poses(np.radians(np.linspace(0, 300, 8)))
    result = synthesize(DyadProblem(poses))
    for center, circle in truth:
        assert _has_pair(result.dyads, center, circle, 1e-5)
    assert result.dyads[0].max_residual < 1e-8
    assert len(result.dyads[0].residuals_mm) == 8


def test_many_poses_report_per_pose_residuals_for_noisy_data(rng):
    poses, truth = fourbar_poses(np.radians(np.linspace(0, 300, 9)))
    noisy = poses + np.c_[rng.normal(scale=0.05, size=(9, 2)), np.zeros(9)]
    result = synthesize(DyadProblem(noisy))
    best = result.dyads[0]
    assert 1e-4 < best.max_residual_mm < 1.0
    spread = np.sqrt(np.mean((best.residuals_mm - best.residuals_mm.mean()) ** 2))
    assert result.rms_mm[0] == pytest.approx(spread, rel=0.5)


def _carrier_chain(rng, count):
    """A 3R chain O-A-F: carrier OA turns by phases about O; the body hangs on F at distance L from A."""
    pivot = np.array([0.0, 0.0])
    hinge = rng.normal(size=2) * 50                     # A in pose 1, on the carrier
    phases = np.radians(np.r_[0, -np.cumsum(rng.uniform(10, 40, count - 1))])
    length = rng.uniform(60, 150)
    pin_in_body = rng.normal(size=2) * 40
    poses = []
    for phase in phases:
        a = rotate_about(hinge, pivot, phase)
        swing = rng.uniform(-np.pi, np.pi)
        f = a + length * np.array([np.cos(swing), np.sin(swing)])
        turn = rng.uniform(-1, 1)
        c, s = np.cos(turn), np.sin(turn)
        poses.append([*(f - np.array([[c, -s], [s, c]]) @ pin_in_body), turn])
    poses = np.array(poses)
    c, s = np.cos(poses[0, 2]), np.sin(poses[0, 2])
    return poses, Link(pivot, phases), hinge, poses[0, :2] + np.array([[c, -s], [s, c]]) @ pin_in_body


def test_relative_motion_five_poses_recover_the_carrier_hinge(rng):
    poses, link, hinge, pin = _carrier_chain(rng, 5)
    result = synthesize(DyadProblem(poses, link=link))
    assert _has_pair(result.dyads, hinge, pin, 1e-7)
    assert all(d.max_residual < 1e-10 for d in result.dyads)


def test_relative_motion_four_poses_curve_contains_the_carrier_hinge(rng):
    poses, link, hinge, pin = _carrier_chain(rng, 4)
    relative = relative_to_link(poses, link.pivot, link.phases)
    frame = Frame.of(relative)
    local = frame.local_poses(relative)
    assert abs(circular_cubic(center_cubic(local), *frame.to_local(hinge))) < 1e-9
    result = synthesize(DyadProblem(poses, link=link, samples=1500, radius_mm=20 * frame.scale))
    assert max(d.max_residual for d in result.dyads) < 1e-9
    # the ground of these dyads turns: a fixed-ground check of the same pivots must fail
    worst = max(verify_dyad(poses, d.center, d.circle).max_residual for d in result.dyads[::50])
    assert worst > 1e-3

"""Checks every mechanism's ``ToleranceModel`` passes, shared by the mechanisms' tests: its exact Jacobian is
central differences of its forward simulation, a planted change moves the key poses by J delta to second
order, and first order meets the Monte Carlo."""
import numpy as np


def assert_jacobian_is_central_differences(analysis) -> None:
    """Every column of the Jacobian within 1e-6 (relative to its largest entry) of central differences of the
    numpy forward simulation at a hundredth of each tolerance (angles wrapped)."""
    model = analysis.model
    n = len(model.nominal)
    step = 1e-2 * model.tolerances
    motion = model.sampled(model.nominal + np.vstack([np.diag(step), -np.diag(step)]))
    difference = (motion[:n] - motion[n:]) / (2 * step[:, None, None])             # (n, rows, T)
    difference[:, 2] = np.angle(np.exp(1j * (motion[:n, 2] - motion[n:, 2]))) / (2 * step[:, None])
    exact = np.moveaxis(analysis.jacobian, -1, 0)
    scale = np.abs(exact).max(axis=2, keepdims=True)
    assert np.all(np.abs(exact - difference) <= 1e-6 * scale + 1e-12), np.max(np.abs(exact - difference) / scale)


def assert_planted_change_is_second_order(analysis, name: str, deltas: tuple[float, float]) -> None:
    """``name`` moved by each of ``deltas`` (the second twice the first) moves the key poses by J delta within
    2 %, and the miss grows fourfold."""
    model = analysis.model
    k = len(model.key_labels)
    nominal = model.sampled(model.nominal[None])[0][:2, :k]
    j = model.names.index(name)
    misses = []
    for delta in deltas:
        moved = model.sampled((model.nominal + delta * np.eye(len(model.nominal))[j])[None])[0][:2, :k]
        predicted = nominal + analysis.jacobian[:2, :k, j] * delta
        misses.append(np.abs(moved - predicted).max())
        assert misses[-1] < 0.02 * np.abs(analysis.jacobian[:2, :k, j] * delta).max()
    assert 3.5 < misses[1] / misses[0] < 4.5             # the miss is of second order in delta


def assert_first_order_meets_monte_carlo(analysis) -> None:
    """Both 3-sigma bands within 10 % of the Monte Carlo's at every key pose, and the report says so."""
    position, angle = analysis.disagreement()
    assert np.all(position <= 0.10) and np.all(angle <= 0.10), (position, angle)
    assert all(pose["first_order_holds"] for pose in analysis.to_json()["key_poses"])
    assert "agree within 10 % at every key pose" in "\n".join(analysis.to_markdown())

"""A mechanism whose motion is linear in its dimensions, for checks with a known answer."""
import casadi as ca
import numpy as np

from transplanter.tolerance import Dimension, ToleranceModel


def linear_model(matrix: np.ndarray, tolerances, condition_limit: float = np.inf) -> ToleranceModel:
    """Motion (3, 1) = matrix (3, n) @ dimensions (nominal 0, mm); one condition: x <= ``condition_limit``."""
    n = matrix.shape[1]
    d, data = ca.SX.sym("d", n), ca.SX.sym("turn", 1)
    at_turn = ca.Function("linear", [d, data], [ca.mtimes(ca.DM(matrix), d) * data])
    dimensions = tuple(Dimension(f"d{i}", 0.0, float(t), "mm") for i, t in enumerate(tolerances))

    def conditions(motion, dims):
        return {"x limit": ~(motion[:, 0, 0] <= condition_limit)}

    return ToleranceModel("linear", dimensions, at_turn, np.ones((1, 1)), lambda dims: (dims @ matrix.T)[:, :, None],
                          np.zeros(1), ("K",), slice(0, None), conditions)

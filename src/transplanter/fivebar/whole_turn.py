"""A design judged over the whole carrier turn by independent forward evaluation: the margins of the
dyad B-E-F, rho', a kappa of the four pitch curves and the lean mu of each mesh's common tangent (the
gear pressure angle's variable part, ``trains.pressure_angle``), with k by the train's own quadrature."""
from __future__ import annotations

import numpy as np

from transplanter._generated.train_pitch_curvature import train_pitch_curvature
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.generated import numpy_twin
from transplanter.geometry.periodic_bspline import TWO_PI, knots
from transplanter.trains.planetary import correction_factor
from transplanter.trains.pressure_angle import stage_leans

#: Carrier turns of the fine check (0.05 deg apart).
CHECK_POINTS = 7200
#: The train's pitch curves, in the order of ``train_pitch_curvature``'s rows.
CURVES = ("sun", "first intermediate", "second intermediate", "planet")
#: The curvature is smooth on a knot span; this far (rad) left of a knot gives its left limit to ~1e-9.
KNOT_SIDE = 1e-9

_curvature = numpy_twin(train_pitch_curvature)


def fine_turns() -> np.ndarray:
    """``CHECK_POINTS`` carrier turns over one turn (rad)."""
    return np.linspace(0, TWO_PI, CHECK_POINTS, endpoint=False)


def knot_left_sides(count: int) -> np.ndarray:
    """Carrier turns just left of the spline's ``count`` knots, where a kappa takes its left limit."""
    return np.mod(knots(count) - KNOT_SIDE, TWO_PI)


def whole_turn(mech: FiveBar, relative: RelativeAngle, turns: np.ndarray | None = None) -> dict:
    """At carrier turns ``turns`` (rad; default ``fine_turns()``): sin^2 of the angles EBF and BEF (forward
    kinematics), rho', a kappa of the four pitch curves (rows of ``CURVES``), k, mu of the two meshes
    (``leans``, rows of ``trains.pressure_angle.STAGES``), and P."""
    turns = fine_turns() if turns is None else turns
    state = mech.forward(turns, relative.evaluate(turns))
    distance = np.linalg.norm(state["f"] - mech.hinge_b, axis=-1)
    slope = [relative.evaluate(turns, order) for order in (1, 2, 3)]
    k = correction_factor(relative)
    curvature = _curvature(slope, [np.full_like(turns, k)])[1]
    return {"turns": turns, "ebf": state["margin"], "bef": state["margin"] * distance**2 / mech.link_length**2,
            "slope": slope[0], "curvature": curvature, "correction": k, "leans": stage_leans(relative, k, turns),
            "p": state["p"]}

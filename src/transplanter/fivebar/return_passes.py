"""Other passes of P by a return point. The design NLP keeps each return point on the pass of P its
start puts it on; where P passes a return point twice, the other pass is a second stroke to try."""
from __future__ import annotations

import numpy as np

from transplanter.fivebar.nlp import MIN_STEP, DesignSolution
from transplanter.fivebar.problem import FiveBarProblem
from transplanter.geometry.periodic_bspline import TWO_PI

#: Carrier turns on which ``other_passes`` looks for the passes of P by the return points (0.1 deg apart).
PASS_POINTS = 3600


def other_passes(problem: FiveBarProblem, design: DesignSolution) -> list[tuple[int, float]]:
    """(return point index, carrier turn in rad) of every other pass of P by a return point that the
    stroke's order allows: each local minimum of |P(c) - P_j| over ``PASS_POINTS`` carrier turns between
    the neighbours' turns (``MIN_STEP`` clear of them; the design's last key pose and a full turn at the ends),
    except the one nearest the design's own turn c_j."""
    turns = np.linspace(0, TWO_PI, PASS_POINTS, endpoint=False)
    p = design.mech.forward(turns, design.relative_angle.evaluate(turns))["p"]
    own, found = design.stroke.carrier_turns, []
    bounds = np.r_[design.carrier_turns[-1], own, TWO_PI]
    for j, point in enumerate(problem.return_points):
        distance = np.linalg.norm(p - point, axis=1)
        minima = np.flatnonzero((distance <= np.roll(distance, 1)) & (distance < np.roll(distance, -1)))
        minima = minima[(turns[minima] > bounds[j] + MIN_STEP) & (turns[minima] < bounds[j + 2] - MIN_STEP)]
        if minima.size:
            nearest = minima[np.argmin(np.abs(turns[minima] - own[j]))]
            found += [(j, float(turns[k])) for k in minima if k != nearest]
    return found

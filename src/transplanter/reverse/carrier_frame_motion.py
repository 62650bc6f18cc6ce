"""The planet's turn against the carrier, chi(c), sampled once as panel polynomials.

``ArmMotion.evaluate`` finds the path parameter of every carrier turn by Newton, which is
too slow to call at every quadrature node of every gear integral. Here chi', chi'' and
chi''' are taken once at the Gauss-Legendre nodes of panels split at the motion's breaks
(spline knots, touches) and kept as the polynomials through them (``TurnMap``); chi itself is
the exact integral of chi', so the gears designed from it and the angle they must produce
agree to quadrature precision.
"""
from __future__ import annotations

import numpy as np

from transplanter.geometry.turn_map import PANELS, TurnMap
from transplanter.geometry.turn_quadrature import panels
from transplanter.reverse.arm_inverse import ArmMotion


class CarrierFrameMotion:
    def __init__(self, motion: ArmMotion):
        self.knots = motion.knots
        nodes = panels(self.knots, PANELS).nodes
        (c1, c2, c3), (h1, h2, h3) = motion.path_rates(motion.parameter_at(nodes))
        derivatives = (h1 / c1, (h2 * c1 - h1 * c2) / c1**3,
                       ((h3 * c1 - h1 * c3) * c1 - 3 * c2 * (h2 * c1 - h1 * c2)) / c1**5)
        self.maps = [TurnMap(lambda _, values=values: values, self.knots) for values in derivatives]

    def evaluate(self, c, order: int = 0) -> np.ndarray:
        """chi (order 0) or its ``order``-th derivative in the carrier turn c, orders 0..3."""
        c = np.mod(np.asarray(c, float), 2 * np.pi)
        return self.maps[0](c) if order == 0 else self.maps[order - 1].rate(c)

"""A monotone map of one turn, F(x) = int_0^x rate(t) dt with rate > 0, and its inverse.

Used for the angle one gear turns while another turns (rate = ratio), and for arc length
along a pitch curve (rate = sqrt(r^2 + r'^2)). The rate is sampled once, at the
Gauss-Legendre nodes of panels split at its breaks; on each panel it is the polynomial
through those nodes (spectrally accurate for a rate smooth between breaks), integrated
exactly. Evaluating F, F' or the inverse (Newton) never calls the rate again, so maps
built on other maps stay cheap.
"""
from __future__ import annotations

import numpy as np
from numpy.polynomial import legendre

from transplanter.geometry.planar import TWO_PI
from transplanter.geometry.turn_quadrature import NODES, panels

#: Panels per turn (2 deg wide, plus the breaks).
PANELS = 180


class TurnMap:
    def __init__(self, rate, breaks=(), count: int = PANELS):
        """``count`` panels per turn (plus the breaks)."""
        self.grid = panels(breaks, count)
        values = rate(self.grid.nodes)
        self.table = self.grid.integrate(values)
        standard, _ = legendre.leggauss(NODES)
        self.coefficients = np.linalg.solve(legendre.legvander(standard, NODES - 1), values.T)
        self.antiderivative = legendre.legint(self.coefficients, lbnd=-1)

    @property
    def total(self) -> float:
        return float(self.table[-1])

    def _locate(self, x):
        edges = self.grid.edges
        k = np.clip(np.searchsorted(edges, x, side="right") - 1, 0, len(edges) - 2)
        half = (edges[k + 1] - edges[k]) / 2
        return k, (x - edges[k]) / half - 1, half

    def __call__(self, x) -> np.ndarray:
        """F(x) for x in [0, 2 pi] (any shape)."""
        x = np.asarray(x, float)
        k, t, half = self._locate(x.ravel())
        inside = legendre.legval(t, self.antiderivative[:, k], tensor=False)
        return (self.table[k] + half * inside).reshape(x.shape)

    def rate(self, x) -> np.ndarray:
        """F'(x), from the panel polynomials."""
        x = np.asarray(x, float)
        k, t, _ = self._locate(x.ravel())
        return legendre.legval(t, self.coefficients[:, k], tensor=False).reshape(x.shape)

    def inverse(self, y, iterations: int = 30) -> np.ndarray:
        """x with F(x) = y, for y in [0, F(2 pi)]."""
        y = np.asarray(y, float)
        x = np.interp(y, self.table, self.grid.edges)
        for _ in range(iterations):
            step = (self(x) - y) / self.rate(x)
            x = np.clip(x - step, 0.0, TWO_PI)
            if np.max(np.abs(step), initial=0.0) < 1e-11:   # Newton: the error left is ~ step^2
                break
        return x

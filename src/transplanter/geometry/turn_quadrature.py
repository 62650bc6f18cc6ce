"""Gauss-Legendre quadrature over one turn, in panels with an edge at every break of a
piecewise integrand (so each piece is integrated on its own)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.geometry.planar import TWO_PI

#: Gauss-Legendre nodes per panel and panels per turn of the working quadrature.
NODES, PANELS = 12, 720
#: Fewest panels between two breaks: a piece narrower than a panel (a denatured ellipse with m11 just above 1/2 has a
#: second piece of 0.07 deg) still gets edges inside it, where its curvature is sampled.
PIECE_PANELS = 8


@dataclass(frozen=True)
class Panels:
    """Quadrature on [0, 2 pi]: panel edges (P + 1), nodes and weights (P, NODES)."""

    edges: np.ndarray
    nodes: np.ndarray
    weights: np.ndarray

    def integrate(self, values: np.ndarray) -> np.ndarray:
        """Integral from 0 to every panel edge, shape (P + 1)."""
        return np.r_[0.0, np.cumsum(np.sum(values * self.weights, axis=1))]


def panels(breaks=(), count: int = PANELS, nodes: int = NODES) -> Panels:
    """Panels about equally wide, with an edge at every break."""
    cuts = np.unique(np.r_[0.0, np.mod(np.asarray(breaks, float), TWO_PI), TWO_PI])
    cuts = cuts[np.r_[True, np.diff(cuts) > 1e-12]]
    edges = []
    for start, end in zip(cuts[:-1], cuts[1:], strict=True):
        pieces = max(PIECE_PANELS, int(round(count * (end - start) / TWO_PI)))
        edges.append(np.linspace(start, end, pieces + 1)[:-1])
    edges = np.r_[np.concatenate(edges), TWO_PI]
    x, w = np.polynomial.legendre.leggauss(nodes)
    half = np.diff(edges)[:, None] / 2
    return Panels(edges, edges[:-1, None] + half * (x + 1), half * w)

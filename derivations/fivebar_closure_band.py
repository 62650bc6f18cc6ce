"""Where the five-bar closes with a margin: the band of the connecting rod's angle at a carrier turn.

In triangle B-E-F (|BE| = L4, |EF| = L3, |BF| = d) the closure margin of eq (10), sin^2 of the angle
EBF (``fivebar.py``), depends on the carrier turn and the relative angle only through d. With
gamma = sqrt(1 - m), the margin is at least m where |L4^2 + d^2 - L3^2| <= 2 gamma L4 d, i.e. where
d^2 - 2 gamma L4 d + L4^2 - L3^2 <= 0 and d^2 + 2 gamma L4 d + L4^2 - L3^2 >= 0: with
r = sqrt(L3^2 - m L4^2),

    |gamma L4 - r| <= d <= gamma L4 + r,

and nowhere when L3^2 < m L4^2 (the angle EBF never exceeds asin(L3 / L4)). The rod A-F (length L2)
places F at d from B exactly where the angle BAF between AB and AF has (law of cosines)

    cos(BAF) = (|AB|^2 + L2^2 - d^2) / (2 |AB| L2),

so the margin is at least m where cos(BAF) lies between the values at d = gamma L4 + r and at
d = |gamma L4 - r|.
"""
from __future__ import annotations

import sympy as sp

from derivations.spec import Derived, symbol_group


def bf_band(l3, l4, margin):
    """(d_low^2, d_high^2): the squared distances |BF|^2 at which sin^2(EBF) equals ``margin``; it is at
    least ``margin`` between them."""
    gamma, root = sp.sqrt(1 - margin), sp.sqrt(l3**2 - margin * l4**2)
    return (gamma * l4 - root)**2, (gamma * l4 + root)**2


def rod_cosine(l2, ab, bf_squared):
    """cos of the angle BAF at A for |AB| = ``ab``, |AF| = ``l2`` and |BF|^2 = ``bf_squared``."""
    return (ab**2 + l2**2 - bf_squared) / (2 * ab * l2)


def derive() -> list[Derived]:
    l2, l3, l4 = chain = symbol_group("chain_lengths", 3)
    ab, margin = symbol_group("frame_distance", 1), symbol_group("margin", 1)
    low, high = bf_band(l3, l4, margin[0])
    return [
        Derived(name="fivebar_closure_band",
                doc="cos(BAF) at |BF| = gamma L4 + r and at |gamma L4 - r| (gamma = sqrt(1 - m), "
                    "r = sqrt(L3^2 - m L4^2)): sin^2(EBF) >= m between them, for (L2, L3, L4), |AB| and m.",
                inputs=(("chain_lengths", chain), ("frame_distance", ab), ("margin", margin)),
                outputs=(("cosines", (rod_cosine(l2, ab[0], high), rod_cosine(l2, ab[0], low))),)),
    ]

"""An optimum's multipliers as plain arrays: a warm start for a re-solve of the same NLP (``Solver.solve``'s
``continues``) that travels with a result between processes, where the ``Solution`` it was read from (which
holds the NLP's CasADi expressions) does not."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.solve.layout import NLPLayout


@dataclass(frozen=True, eq=False)
class Multipliers:
    """The multipliers of the variables' bounds (``lam_x``) and of the rows (``lam_g``), in CasADi's sign."""

    lam_x: np.ndarray
    lam_g: np.ndarray

    def fits(self, layout: NLPLayout) -> bool:
        """Whether they are sized for ``layout``'s variables and rows."""
        return self.lam_x.shape == (layout.x.shape[0],) and self.lam_g.shape == (layout.g.shape[0],)

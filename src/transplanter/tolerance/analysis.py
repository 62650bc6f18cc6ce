"""``analyse``: first-order bands, Monte Carlo, variance shares, margins and allocation of a built mechanism."""
from __future__ import annotations

import time
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np

from transplanter.errors import SolverError
from transplanter.figure_conventions import FigureDrawer, drawn
from transplanter.tolerance.allocation import Allocation, allocate
from transplanter.tolerance.bands import (
    position_covariance,
    relative_difference,
    statistical_bands,
    variance_shares,
    worst_case_bands,
)
from transplanter.tolerance.dimensions import ToleranceSettings
from transplanter.tolerance.model import ToleranceModel
from transplanter.tolerance.monte_carlo import MonteCarlo, monte_carlo

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: First order and Monte Carlo "agree" at a key pose when their 3-sigma bands differ by at most this fraction.
AGREEMENT = 0.10


class Toleranced(Protocol):
    """A design result that can say how its built mechanism depends on its manufactured dimensions."""

    def tolerance_model(self) -> ToleranceModel: ...


@dataclass(frozen=True)
class ToleranceAnalysis:
    """How precise the built mechanism will be.

    Attributes
    ----------
    model : ToleranceModel
        The mechanism, its dimensions carrying the tolerances analysed.
    settings : ToleranceSettings
        Distribution, samples, seed and the accuracy the key poses need.
    jacobian : ndarray, shape (rows, T, n)
        d motion / d dimension at the nominal design (automatic differentiation), per unit of each dimension.
    first_order_3sigma_mm, first_order_3sigma_deg, worst_case_mm, worst_case_deg : ndarray, shape (T,)
        Bands of P (mm) and the plate angle (deg) at every column of the motion (``bands``).
    monte_carlo : MonteCarlo
        The nonlinear mechanism's bands and the hard conditions' violation fractions.
    position_shares, angle_shares : ndarray, shape (K, n)
        Each dimension's share of each key pose's variance.
    allocation : Allocation or None
        The loosest tolerances meeting the required accuracy (None where the allocation did not converge,
        with the reason in ``allocation_note``).
    timings_s : dict
        Wall time of the Jacobian, the Monte Carlo and the allocation (s).
    """

    model: ToleranceModel
    settings: ToleranceSettings
    jacobian: np.ndarray
    first_order_3sigma_mm: np.ndarray
    first_order_3sigma_deg: np.ndarray
    worst_case_mm: np.ndarray
    worst_case_deg: np.ndarray
    monte_carlo: MonteCarlo
    position_shares: np.ndarray
    angle_shares: np.ndarray
    allocation: Allocation | None
    allocation_note: str
    timings_s: dict

    @property
    def key_count(self) -> int:
        return len(self.model.key_labels)

    @property
    def sigma(self) -> np.ndarray:
        return self.model.tolerances * self.settings.sigma_per_tolerance

    def key_covariance(self) -> np.ndarray:
        """First-order position covariance (K, 2, 2) at the key poses (mm^2)."""
        return position_covariance(self.jacobian[:2, :self.key_count], self.sigma)

    def largest_contributions(self, count: int = 3) -> list[tuple[str, float]]:
        """The ``count`` dimensions with the largest mean share of the key poses' position variance."""
        mean = self.position_shares.mean(axis=0)
        order = np.argsort(mean)[::-1][:count]
        return [(self.model.names[i], float(mean[i])) for i in order]

    def disagreement(self) -> tuple[np.ndarray, np.ndarray]:
        """|Monte Carlo / first order - 1| of the key poses' 3-sigma position and angle bands."""
        k, mc = self.key_count, self.monte_carlo
        return (relative_difference(mc.position_3sigma_mm[:k], self.first_order_3sigma_mm[:k]),
                relative_difference(mc.angle_3sigma_deg[:k], self.first_order_3sigma_deg[:k]))

    def to_json(self) -> dict[str, Any]:
        from transplanter.tolerance.report import tolerance_json

        return tolerance_json(self)

    def to_markdown(self) -> list[str]:
        from transplanter.tolerance.report import tolerance_markdown

        return tolerance_markdown(self)

    def figure_drawers(self) -> dict[str, FigureDrawer]:
        """The figures by file stem, each drawn when called."""
        from transplanter.tolerance.figures import figure_drawers

        return figure_drawers(self)

    def draw_figures(self) -> dict[str, Figure]:
        return drawn(self.figure_drawers())


def _settings(tolerances: ToleranceSettings | Mapping[str, float] | None) -> ToleranceSettings:
    if isinstance(tolerances, ToleranceSettings):
        return tolerances
    return ToleranceSettings(dict(tolerances or {}))


def analyse(subject: Toleranced | ToleranceModel,
            tolerances: ToleranceSettings | Mapping[str, float] | None = None) -> ToleranceAnalysis:
    """The tolerance analysis of a design result (or of a mechanism's ``ToleranceModel``).

    ``tolerances`` is a ``ToleranceSettings`` (what a ``[tolerances]`` table gives) or a mapping of dimension
    names to tolerances (mm or deg, the dimension's unit); None takes every default. An unknown name is a
    ``ProblemError``.
    """
    model = subject if isinstance(subject, ToleranceModel) else subject.tolerance_model()
    settings = _settings(tolerances)
    defaults = model.tolerances
    model = model.with_dimensions(settings.applied(model.dimensions))
    timings = {}
    start = time.perf_counter()
    jacobian = model.jacobian()
    timings["jacobian"] = time.perf_counter() - start
    sigma = model.tolerances * settings.sigma_per_tolerance
    position, angle = statistical_bands(jacobian, sigma)
    worst_position, worst_angle = worst_case_bands(jacobian, model.tolerances)
    start = time.perf_counter()
    sampled = monte_carlo(model, settings.samples, settings.seed, settings.distribution)
    timings["monte_carlo"] = time.perf_counter() - start
    k = len(model.key_labels)
    position_shares, angle_shares = variance_shares(jacobian[:, :k], sigma)
    start = time.perf_counter()
    try:
        allocation, note = allocate(jacobian[:3, :k], defaults, settings.sigma_per_tolerance, model.key_labels,
                                    settings.pose_position_mm, settings.pose_angle_deg), ""
    except SolverError as error:       # the report says so instead of failing the design
        allocation, note = None, str(error)
    timings["allocation"] = time.perf_counter() - start
    return ToleranceAnalysis(model, settings, jacobian, position, angle, worst_position, worst_angle, sampled,
                             position_shares, angle_shares, allocation, note, timings)

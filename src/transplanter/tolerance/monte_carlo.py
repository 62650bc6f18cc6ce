"""Monte Carlo of the nonlinear built mechanism: every toleranced dimension drawn at once, N mechanisms at once.

Samples are drawn by a seeded generator (``uniform``: nominal + t U(-1, 1); ``normal``: nominal + t / 3 N(0, 1))
and the mechanism's ``sampled`` motion closes them in arrays, ``CHUNK`` mechanisms per pass, with no loop
over samples; the chunks are shared between this process and a side process where the machine gives a
second core (``shared_calls``). Deviations are taken from the nominal motion (plate angles wrapped to (-pi, pi]);
a mechanism that does not close (NaN) is counted and left out of the statistics, and violates the closure
condition.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.shared_calls import shared_map
from transplanter.tolerance.bands import largest_eigenvalue
from transplanter.tolerance.model import ToleranceModel

#: Mechanisms closed per array pass: their arrays stay in cache (500 take a third of the time 10,000 at once do).
CHUNK = 500


@dataclass(frozen=True)
class MonteCarlo:
    """N built mechanisms: 3-sigma position (mm) and angle (deg) bands and the position covariance (T, 2, 2)
    per column, each hard condition's violation fraction, and how many did not close."""

    samples: int
    position_3sigma_mm: np.ndarray
    angle_3sigma_deg: np.ndarray
    covariance: np.ndarray
    violation_fraction: dict[str, float]
    not_closing: int


def draw(model: ToleranceModel, samples: int, seed: int, distribution: str) -> np.ndarray:
    """(samples, n) dimensions of built mechanisms."""
    rng = np.random.default_rng(seed)
    shape = (samples, len(model.dimensions))
    unit = rng.uniform(-1.0, 1.0, shape) if distribution == "uniform" else rng.standard_normal(shape) / 3
    return model.nominal + model.tolerances * unit


def monte_carlo(model: ToleranceModel, samples: int, seed: int, distribution: str) -> MonteCarlo:
    dimensions = draw(model, samples, seed, distribution)
    parts = np.array_split(dimensions, -(-samples // CHUNK))
    motion = np.concatenate(shared_map(model.sampled, [(part,) for part in parts]))
    nominal = model.sampled(model.nominal[None])[0]
    position = motion[:, :2] - nominal[:2]
    angle = np.angle(np.exp(1j * (motion[:, 2] - nominal[2])))
    closes = np.all(np.isfinite(motion[:, :3]), axis=(1, 2))
    position, angle = position[closes], angle[closes]
    centred = position - position.mean(axis=0)
    covariance = np.einsum("nit,njt->tij", centred, centred) / max(len(centred) - 1, 1)
    violated = model.conditions(motion, dimensions)
    return MonteCarlo(samples, 3 * np.sqrt(largest_eigenvalue(covariance)), np.degrees(3 * angle.std(axis=0, ddof=1)),
                      covariance, {name: float(np.mean(flags)) for name, flags in violated.items()},
                      int(samples - closes.sum()))

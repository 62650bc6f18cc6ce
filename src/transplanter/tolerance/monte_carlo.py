"""Monte Carlo of the nonlinear built mechanism: every toleranced dimension drawn at once, N mechanisms at once.

Samples are drawn by a seeded generator (``uniform``: nominal + t U(-1, 1); ``normal``: nominal + t / 3 N(0, 1))
and the mechanism's ``sampled`` motion closes them in arrays, ``CHUNK`` mechanisms per pass, with no loop
over samples; the chunks are shared between this process and a side process where the machine gives a
second core (``shared_calls``). Deviations are taken from the nominal motion (plate angles wrapped to (-pi, pi]);
a mechanism that does not close (NaN) is counted and left out of the statistics, and violates the closure
condition.
"""
from __future__ import annotations

import operator
from dataclasses import dataclass
from functools import partial, reduce

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


@dataclass(frozen=True)
class _Tally:
    """What a chunk of built mechanisms adds to the statistics: how many close, the sums of their deviations
    (position (2, T), angle (T,)) and of their squares (position products (T, 2, 2), angle (T,)), and how many
    violate each hard condition."""

    closing: int
    position: np.ndarray
    position_products: np.ndarray
    angle: np.ndarray
    angle_squares: np.ndarray
    violations: dict[str, int]

    def __add__(self, other: _Tally) -> _Tally:
        return _Tally(self.closing + other.closing, self.position + other.position,
                      self.position_products + other.position_products, self.angle + other.angle,
                      self.angle_squares + other.angle_squares,
                      {name: count + other.violations[name] for name, count in self.violations.items()})


def _tally(model: ToleranceModel, nominal: np.ndarray, dimensions: np.ndarray) -> _Tally:
    """Close the built mechanisms of ``dimensions`` (N, n) and tally their deviations from the ``nominal`` motion."""
    motion = model.sampled(dimensions)
    closes = np.all(np.isfinite(motion[:, :3]), axis=(1, 2))
    position = motion[closes, :2] - nominal[:2]
    angle = np.angle(np.exp(1j * (motion[closes, 2] - nominal[2])))
    return _Tally(int(closes.sum()), position.sum(axis=0), np.einsum("nit,njt->tij", position, position),
                  angle.sum(axis=0), (angle ** 2).sum(axis=0),
                  {name: int(flags.sum()) for name, flags in model.conditions(motion, dimensions).items()})


def monte_carlo(model: ToleranceModel, samples: int, seed: int, distribution: str) -> MonteCarlo:
    dimensions = draw(model, samples, seed, distribution)
    nominal = model.sampled(model.nominal[None])[0]
    parts = np.array_split(dimensions, -(-samples // CHUNK))
    tally = reduce(operator.add, shared_map(partial(_tally, model, nominal), [(part,) for part in parts]))
    n, mean = tally.closing, tally.position / max(tally.closing, 1)
    covariance = (tally.position_products - n * np.einsum("it,jt->tij", mean, mean)) / max(n - 1, 1)
    angle_variance = (tally.angle_squares - tally.angle ** 2 / max(n, 1)) / max(n - 1, 1)
    return MonteCarlo(samples, 3 * np.sqrt(largest_eigenvalue(covariance)),
                      np.degrees(3 * np.sqrt(np.maximum(angle_variance, 0))), covariance,
                      {name: count / samples for name, count in tally.violations.items()}, samples - n)

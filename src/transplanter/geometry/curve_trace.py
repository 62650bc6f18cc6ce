"""Complete sampling of a circular cubic (eq 2) by the pencil of lines through one of its points.

Every point of the curve other than ``pivot`` lies on exactly one line through it, and
that line meets the curve again in the roots of a quadratic (``circular_cubic_pencil``).
Sweeping the line direction over half a turn therefore visits every real branch, ovals
included; nothing depends on a starting guess.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.burmester import circular_cubic_pencil
from transplanter.generated import numpy_twin

_pencil = numpy_twin(circular_cubic_pencil)


@dataclass(frozen=True)
class CurveTrace:
    """Sampled points (N, 2) of a curve and the runs of consecutive indices that draw it."""

    points: np.ndarray
    runs: list[np.ndarray]


def _pencil_roots(alpha, beta, gamma):
    """Both roots of alpha t^2 + beta t + gamma, each computed without cancellation; NaN where complex."""
    root = np.sqrt(np.where(beta**2 - 4 * alpha * gamma >= 0, beta**2 - 4 * alpha * gamma, np.nan))
    with np.errstate(divide="ignore", invalid="ignore"):
        big_plus = (-beta + root) / (2 * alpha)
        big_minus = (-beta - root) / (2 * alpha)
        small_plus = 2 * gamma / (-beta - root)
        small_minus = 2 * gamma / (-beta + root)
    plus = np.where(beta < 0, big_plus, small_plus)
    minus = np.where(beta < 0, small_minus, big_minus)
    return plus, minus


def trace_circular_cubic(coefficients, pivot, directions: int, radius: float) -> CurveTrace:
    """Points of the cubic within ``radius`` of the origin, ``directions`` lines through ``pivot``."""
    angles = np.pi * np.arange(directions) / directions
    direction = np.stack([np.cos(angles), np.sin(angles)])
    alpha, beta, gamma = _pencil(np.asarray(coefficients)[:, None], np.asarray(pivot)[:, None], direction)[0]
    sheets: list[np.ndarray] = []
    runs: list[np.ndarray] = []
    start = 0
    for t in _pencil_roots(alpha, beta, gamma):
        sheet = pivot[:, None] + t * direction
        inside = np.isfinite(t) & (np.hypot(*sheet) <= radius)
        sheets.append(sheet.T[inside])
        index = np.flatnonzero(inside)
        for run in np.split(np.arange(index.size), np.flatnonzero(np.diff(index) > 1) + 1):
            if run.size > 1:
                runs.append(start + run)
        start += index.size
    points = np.concatenate(sheets)
    return CurveTrace(points, _split_jumps(points, runs, radius))


def _split_jumps(points, runs, radius):
    """Cut runs where consecutive samples jump across the window (a branch through infinity)."""
    out = []
    for run in runs:
        step = np.linalg.norm(np.diff(points[run], axis=0), axis=1)
        out.extend(piece for piece in np.split(run, np.flatnonzero(step > 0.25 * radius) + 1) if piece.size > 1)
    return out

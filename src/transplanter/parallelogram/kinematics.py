"""The mechanism of the onion-transplanter paper as numpy arrays over many designs at once: gear pair, crank phase,
crank pin and planting point with exact velocity and acceleration (generated ``parallelogram``).

Every parameter is an array of one value per design (shape (P,)); angles are evaluated on
arrays whose first axis is the design. The driver angle phi1 may run past one turn: the
generated functions take phi1 within [0, 2 pi] and each further turn adds phi2(2 pi) to the
crank (2 pi when the pair closes).
"""
from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass

import numpy as np

from transplanter._generated.gears import limacon_center_distance
from transplanter._generated.parallelogram import limacon_driven_angle, parallelogram_position, parallelogram_tip
from transplanter.gears.pitch_curves import denatured_partner
from transplanter.generated import numpy_twin
from transplanter.geometry.planar import TWO_PI
from transplanter.parallelogram.problem import Conventions, ParallelogramProblem

_driven = numpy_twin(limacon_driven_angle)
_tip = numpy_twin(parallelogram_tip)
_position = numpy_twin(parallelogram_position)
_closing = numpy_twin(limacon_center_distance)


def closing_center_distance(base, amplitude) -> np.ndarray:
    """Center distance (mm) at which the denatured limacon closes with a driven gear of order 1.

    With eq (2) a whole turn of phi2 equals the plain limacon's (derivations/parallelogram.py), so
    this is the gear library's closed form ``limacon_center_distance`` at order ratio 1.
    """
    return _closing([base], [amplitude], [np.ones_like(np.asarray(base, float))])[0][0]


def _group(*values) -> np.ndarray:
    """One input group of a generated function: its members broadcast to one shape."""
    return np.array(np.broadcast_arrays(*values))


def _column(value, ndim: int) -> np.ndarray:
    """A per-design array shaped to broadcast against angles of ``ndim`` dimensions (design first)."""
    value = np.asarray(value, float)
    return value.reshape(value.shape + (1,) * (ndim - value.ndim))


#: The attributes of ``Mechanisms`` that hold one value per design.
_PER_DESIGN = ("m11", "m12", "amplitude", "base_radius", "center_distance", "l1", "l2", "l5", "l6", "alpha")


@dataclass(frozen=True)
class Mechanisms:
    """P designs of the mechanism (mm, rad, s); every attribute has shape (P,).

    ``m12`` and ``center_distance`` are eq (2) and closure unless a printed value is evaluated.
    ``pivot`` is O2 in the driver's frame: the driven center (a, 0) plus the file's offset.
    """

    m11: np.ndarray
    m12: np.ndarray
    amplitude: np.ndarray           # the driver's b: r1 = l + b cos(m phi1) on each half
    base_radius: np.ndarray         # the driver's l
    center_distance: np.ndarray
    l1: np.ndarray
    l2: np.ndarray
    l5: np.ndarray
    l6: np.ndarray
    alpha: np.ndarray
    conventions: Conventions
    driver_speed: float
    forward_velocity: float
    pivot_offset: np.ndarray

    @property
    def count(self) -> int:
        return self.m11.size

    def first(self) -> Mechanisms:
        """The first design alone: every per-design attribute cut to shape (1,)."""
        return dataclasses.replace(self, **{name: getattr(self, name)[:1] for name in _PER_DESIGN})

    def pitch(self, ndim: int) -> np.ndarray:
        return _group(*(_column(v, ndim) for v in (self.base_radius, self.amplitude, self.m11, self.m12)))

    def driven_angle(self, phi1) -> np.ndarray:
        """phi2 at driver angles within one turn (design on the first axis)."""
        phi1 = np.asarray(phi1, float)
        return _driven([phi1], self.pitch(phi1.ndim), [_column(self.center_distance, phi1.ndim)])[0][0]

    @functools.cached_property
    def driven_turn(self) -> np.ndarray:
        """phi2 after one driver turn: 2 pi when the pair closes."""
        return self.driven_angle(np.full(self.count, TWO_PI))

    @functools.cached_property
    def crank_phase(self) -> np.ndarray:
        """theta - sense phi2: reference - sense (phi2(phi1_ref) + alpha) (problem.py, conventions)."""
        c = self.conventions
        instant = np.pi / self.m11 if c.alpha_instant == "slowest" else np.zeros(self.count)
        return c.alpha_reference - c.crank_sense * (self.driven_angle(instant) + self.alpha)

    def _groups(self, phi1: np.ndarray):
        """Generated-function inputs at driver angles ``phi1`` (any turn): local angle, pitch, center
        distance, links and crank (phase advanced by phi2(2 pi) per whole turn)."""
        nd = phi1.ndim
        laps = np.floor(phi1 / TWO_PI)
        local = phi1 - TWO_PI * laps
        sense = self.conventions.crank_sense
        phase = _column(self.crank_phase, nd) + sense * laps * _column(self.driven_turn, nd)
        pivot = (_column(self.center_distance + self.pivot_offset[0], nd),
                 _column(np.full(self.count, self.pivot_offset[1]), nd))
        links = _group(*(_column(v, nd) for v in (self.l1, self.l2, self.l5, self.l6)))
        crank = _group(phase, sense * np.ones_like(phase), *pivot)
        return [local], self.pitch(nd), [_column(self.center_distance, nd)], links, crank

    def state(self, phi1) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """(crank pin A, planting point E in the field, velocity, acceleration) at driver angles
        ``phi1`` (rad, any turn; t = phi1 / omega1), each of shape (2, *phi1.shape)."""
        phi1 = np.asarray(phi1, float)
        angle, pitch, center, links, crank = self._groups(phi1)
        ones = np.ones_like(crank[0])
        motion = _group(self.driver_speed * ones, self.forward_velocity * ones)
        pin, tip, velocity, acceleration = _tip(angle, [phi1 / self.driver_speed], pitch, center, links, crank, motion)
        return pin, tip, velocity, acceleration

    def position(self, phi1) -> np.ndarray:
        """E in the machine's frame (no forward motion), shape (2, *phi1.shape): for dense grids."""
        phi1 = np.asarray(phi1, float)
        return _position(*self._groups(phi1))[0]


def mechanisms(problem: ParallelogramProblem, variables: dict | None = None, m12=None,
               center_distance=None) -> Mechanisms:
    """Mechanisms for ``variables`` (name -> value or array; the problem's design fills the rest).

    ``m12`` and ``center_distance`` replace eq (2) and closure (to evaluate printed values).
    """
    values = {**problem.design, **(variables or {})}
    count = max(np.size(v) for v in values.values())
    arrays = {k: np.broadcast_to(np.asarray(v, float), (count,)).copy() for k, v in values.items()}
    m12 = denatured_partner(arrays["m11"]) if m12 is None else np.broadcast_to(float(m12), (count,)).copy()
    a = (closing_center_distance(arrays["l"], arrays["b"]) if center_distance is None
         else np.broadcast_to(float(center_distance), (count,)).copy())
    return Mechanisms(m11=arrays["m11"], m12=m12, amplitude=arrays["b"], base_radius=arrays["l"], center_distance=a,
                      l1=arrays["l1"], l2=arrays["l2"], l5=arrays["l5"], l6=arrays["l6"], alpha=arrays["alpha"],
                      conventions=problem.conventions, driver_speed=problem.driver_speed,
                      forward_velocity=problem.forward_velocity, pivot_offset=np.asarray(problem.crank_pivot, float))

"""Forces and torques in a five-bar design over one carrier turn, for a planting load at P and the links' weights.

Model (``derivations/fivebar_statics.py``): quasi-static, frictionless hinges, a lossless gear train. The train is
taken to pass pure torques: it turns rod AF about A by ``planet_torque`` and takes the reaction on the carrier and
the frame's fixed sun; the resultants of its mesh forces, about a train torque over a pitch radius, are left out,
so the hinges A and O carry the link forces alone.

By virtual work through the derived velocities: the carrier's input torque balances the loads' power per unit
carrier turn (theta1' = -1, theta2' = rho' - 1); the train's torque on the rod balances it per unit turn of the rod
about A with the carrier held (theta1' = 0, theta2' = 1). The force at E solves the closure matrix transposed
(the loads' moments about B and F); the force in BE is its part along E -> B, and the other hinges follow from
each link's balance of forces, outward from E: F (the plate), A (the rod), O (the carrier), B (the receiving plate).
Lengths are mm inside, forces N, torques N m.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter._generated.fivebar_statics import fivebar_statics_plate_hinge_force, fivebar_statics_velocities
from transplanter.errors import InfeasibleError
from transplanter.fivebar.linkage import FiveBar
from transplanter.fivebar.load_spec import GRAVITY, LINKS, LoadSpec
from transplanter.fivebar.relative_angle import RelativeAngle
from transplanter.generated import numpy_twin, signature
from transplanter.geometry.planar import TWO_PI, cross, unit

#: Carrier turns over which the forces are evaluated (0.5 deg apart).
TURN_SAMPLES = 720
#: Hinges whose forces are reported, and what each force acts on: O frame -> carrier, A carrier -> rod,
#: F rod -> plate, E receiving plate -> plate, B frame -> receiving plate.
HINGES = ("O", "A", "B", "E", "F")
#: A key turn this close (rad) to a grid turn counts the grid turn into the stroke.
STROKE_TOLERANCE = 1e-9
#: The derived velocity of each link's centre, by link.
_CENTER_OUTPUTS = dict(zip(LINKS, ("carrier_center", "rod_center", "plate_center", "receiving_center"), strict=True))
_MM_PER_M = 1000.0

_velocities = numpy_twin(fivebar_statics_velocities)
_plate_hinge_force = numpy_twin(fivebar_statics_plate_hinge_force)
_VELOCITY_NAMES = [name for name, _ in signature(fivebar_statics_velocities)[1]]


@dataclass(frozen=True)
class Kinetostatics:
    """Forces (N) and torques (N m) of a design over one carrier turn, one row per turn.

    Attributes
    ----------
    turns : ndarray (n,)
        Carrier turns, clockwise (rad).
    stroke : (float, float)
        The pushing stroke: the first and last key pose's carrier turn (rad).
    load : LoadSpec
        The load and masses applied.
    force_at_p : ndarray (n, 2)
        The planting force at P (N): zero off the stroke.
    carrier_torque : ndarray (n,)
        Torque of the drive on the carrier about O, positive clockwise (the carrier's sense): positive where the
        drive does work (N m).
    planet_torque : ndarray (n,)
        Torque of the gear train on rod AF about A, counterclockwise positive (N m).
    be_force : ndarray (n,)
        Force in the receiving plate BE along its line, tension positive (N).
    hinge_forces : dict
        Per name of ``HINGES``, the force vectors (n, 2) (N), on the link ``HINGES`` says.
    """

    turns: np.ndarray
    stroke: tuple[float, float]
    load: LoadSpec
    force_at_p: np.ndarray
    carrier_torque: np.ndarray
    planet_torque: np.ndarray
    be_force: np.ndarray
    hinge_forces: dict

    @property
    def on_stroke(self) -> np.ndarray:
        """Which ``turns`` lie on the pushing stroke."""
        return on_stroke(self.turns, self.stroke)

    def hinge_magnitudes(self) -> dict:
        """|force| at each hinge (N), arrays (n,)."""
        return {name: np.hypot(*force.T) for name, force in self.hinge_forces.items()}

    def peaks(self) -> dict:
        """(value, carrier turn in rad) where each quantity is largest in magnitude: ``carrier_torque``,
        ``planet_torque``, ``be_force`` (signed values) and each hinge's force magnitude."""
        series = {"carrier_torque": self.carrier_torque, "planet_torque": self.planet_torque,
                  "be_force": self.be_force, **self.hinge_magnitudes()}
        return {name: peak(values, self.turns) for name, values in series.items()}


def peak(values: np.ndarray, turns: np.ndarray) -> tuple[float, float]:
    """The value of largest magnitude (signed) and the turn where it occurs."""
    k = int(np.argmax(np.abs(values)))
    return float(values[k]), float(turns[k])


def on_stroke(turns: np.ndarray, stroke: tuple[float, float]) -> np.ndarray:
    """Which ``turns`` lie on the pushing ``stroke`` (first and last key turn, rad), ends included."""
    return (turns >= stroke[0] - STROKE_TOLERANCE) & (turns <= stroke[1] + STROKE_TOLERANCE)


def grid_turns(samples: int = TURN_SAMPLES) -> np.ndarray:
    """``samples`` carrier turns evenly over one turn (rad)."""
    return np.linspace(0.0, TWO_PI, samples, endpoint=False)


def link_weights(load: LoadSpec) -> dict:
    """Weight vector of each link (N), gravity along -y."""
    return {link: np.array([0.0, -mass * GRAVITY]) for link, mass in load.masses_kg.items()}


def _plate_points(mech: FiveBar) -> list:
    """(e_x, e_y, f_x, f_y): E and F in the plate's frame (mm)."""
    return [*mech.e_local, *mech.f_local]


def _closed_loop(mech: FiveBar, relative: RelativeAngle, turns: np.ndarray) -> dict:
    """``FiveBar.forward`` at ``turns`` with the absolute angles (theta1, theta2, theta4, phi) and rho'."""
    rho = relative.evaluate(turns)
    loop = mech.forward(turns, rho)
    if not np.all(loop["margin"] >= 0):
        where = np.degrees(turns[np.argmin(np.nan_to_num(loop["margin"], nan=-np.inf))])
        raise InfeasibleError(f"kinetostatics: the chain B-E-F does not close at carrier turn {where:.2f} deg; the "
                              "loads need a design whose closure margin stays above 0 all round")
    theta1 = mech.carrier_angle - turns
    receiving = loop["e"] - mech.hinge_b
    loop["angles"] = [theta1, theta1 + rho, np.arctan2(receiving[:, 1], receiving[:, 0]), loop["direction"]]
    loop["slope"] = relative.evaluate(turns, 1)
    return loop


def _motion(mech: FiveBar, angles: list, rates: list) -> dict:
    """The derived velocities for rates (theta1', theta2'), by output name, as arrays (n, 2)."""
    lengths = [mech.carrier_length, mech.rod_length, mech.receiving_length]
    values = _velocities(lengths, angles, _plate_points(mech), rates)
    return {name: np.moveaxis(value, 0, -1) for name, value in zip(_VELOCITY_NAMES, values, strict=True)}


def _jacobians(mech: FiveBar, loop: dict) -> tuple[dict, dict]:
    per_turn = _motion(mech, loop["angles"], [np.full_like(loop["slope"], -1.0), loop["slope"] - 1.0])
    return per_turn, _motion(mech, loop["angles"], [0.0, 1.0])


def jacobians(mech: FiveBar, relative: RelativeAngle, turns: np.ndarray) -> tuple[dict, dict]:
    """Velocities (mm/rad, arrays (n, 2)) of A, F, E, P and the link centres, named as the outputs of
    ``fivebar_statics_velocities``, per unit carrier turn (clockwise) and per unit turn of the rod about A with
    the carrier held.

    Raises
    ------
    InfeasibleError
        The chain does not close at some turn.
    """
    return _jacobians(mech, _closed_loop(mech, relative, np.asarray(turns, float)))


def _planting_force(load: LoadSpec, velocity_p: np.ndarray, pushing: np.ndarray) -> np.ndarray:
    """The force at P (N, (n, 2)): ``force_n``, or ``resisting_n`` against P's velocity, on the stroke only."""
    if load.force_n is not None:
        return np.where(pushing[:, None], load.force_n, 0.0)
    assert load.resisting_n is not None, "LoadSpec sets resisting_n when force_n is None"
    speed = np.hypot(*velocity_p.T)[:, None]
    direction = np.divide(velocity_p, speed, out=np.zeros_like(velocity_p), where=speed > 0)
    return np.where(pushing[:, None], -load.resisting_n * direction, 0.0)


def _power(force_at_p: np.ndarray, weights: dict, motion: dict) -> np.ndarray:
    """Power of the planting force and the weights (N mm per unit rate) for the velocities ``motion``."""
    power = np.einsum("ni,ni->n", force_at_p, motion["point_p"])
    for link, weight in weights.items():
        power = power + motion[_CENTER_OUTPUTS[link]] @ weight
    return power


def kinetostatics(mech: FiveBar, relative: RelativeAngle, key_turns: np.ndarray, load: LoadSpec,
                  turns: np.ndarray | None = None) -> Kinetostatics:
    """Forces and torques of the design (``mech``, rod angle ``relative``) under ``load`` over one turn.

    Parameters
    ----------
    mech, relative
        The five-bar (mm, rad) and rho(c).
    key_turns : ndarray
        The key poses' carrier turns (rad): the pushing stroke runs from the first to the last.
    load : LoadSpec
        The planting load and the links' masses.
    turns : ndarray, optional
        Carrier turns (rad); default ``TURN_SAMPLES`` over the turn.

    Raises
    ------
    InfeasibleError
        The chain does not close at some turn (no forces there).
    """
    turns = grid_turns() if turns is None else np.asarray(turns, float)
    loop = _closed_loop(mech, relative, turns)
    per_turn, per_rod_turn = _jacobians(mech, loop)
    e, f, p = loop["e"], loop["f"], loop["p"]
    theta4, phi = loop["angles"][2:]
    stroke = (float(key_turns[0]), float(key_turns[-1]))
    force_at_p = _planting_force(load, per_turn["point_p"], on_stroke(turns, stroke))
    weights = link_weights(load)

    # moments (N mm) about B of BE's weight and about F of the loads on the plate
    moment_b = cross((e - mech.hinge_b) / 2, weights["receiving_plate"])
    moment_f = cross(p - f, force_at_p) + cross((e + p - 2 * f) / 3, weights["plate"])
    force_e = np.moveaxis(_plate_hinge_force([mech.receiving_length], [theta4, phi], _plate_points(mech),
                                             [moment_b, moment_f])[0], 0, -1)
    force_f = -(force_e + force_at_p + weights["plate"])
    force_a = force_f - weights["rod"]
    hinge_forces = {"O": force_a - weights["carrier"], "A": force_a, "B": force_e - weights["receiving_plate"],
                    "E": force_e, "F": force_f}
    return Kinetostatics(
        turns=turns, stroke=stroke, load=load, force_at_p=force_at_p,
        carrier_torque=-_power(force_at_p, weights, per_turn) / _MM_PER_M,
        planet_torque=-_power(force_at_p, weights, per_rod_turn) / _MM_PER_M,
        be_force=np.einsum("ni,ni->n", force_e, unit(theta4 + np.pi)),
        hinge_forces={name: hinge_forces[name] for name in HINGES})

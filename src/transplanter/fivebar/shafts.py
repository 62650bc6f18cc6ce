"""The five-bar's shafts, hinge pins and keyed gear bores, from ``[shafts]`` and the loads.

The sun is keyed to the frame's fixed shaft at O, both intermediate gears to the carrier's intermediate shaft and
the planet, with rod AF, to the shaft at A. Through the lossless train each shaft's torque follows from the
train's torque on the rod, T_planet(c) (``fivebar.kinetostatics``), by the rates of the gears against the carrier:
T_intermediate = T_planet rho'(c) / psi'(c) and T_sun = T_planet rho'(c). A shaft not given is sized from its
peak torque over the turn, the hinge pins at B, E and F from the largest force on any of them over the turn
(``shafts.sizing``); each gear's keyway sits on its assembly mark (towards the contact point at pose 1) and is
checked against the gear's root.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from transplanter.fivebar.gears_on_carrier import gears_on_carrier
from transplanter.fivebar.kinetostatics import Kinetostatics
from transplanter.fivebar.shaft_spec import ShaftSpec
from transplanter.shafts.keyed_bore import KeyedBore
from transplanter.shafts.sizing import diameter_for_pin, diameter_for_torque, rim_failures
from transplanter.trains.toothed_train import ToothedTrain

#: The shaft each gear is keyed to.
SHAFT_OF_GEAR = {"sun": "sun", "first_intermediate": "intermediate", "second_intermediate": "intermediate",
                 "planet": "planet"}
#: The hinges the pins make (O and A are the keyed sun and planet shafts).
PINNED_HINGES = ("B", "E", "F")


@dataclass(frozen=True)
class Shaft:
    """A shaft or the hinge pins: diameter (mm), peak torque (N m; None for the pins), how it was chosen and, for
    the pins, the peak force on them (N)."""

    name: str
    diameter: float
    peak_torque_nm: float | None
    rule: str
    peak_force_n: float | None = None


@dataclass(frozen=True)
class ShaftDesign:
    """The shafts by name (sun, intermediate, planet, hinge), each gear's keyed bore and root radius (mm)."""

    shafts: dict[str, Shaft]
    bores: dict[str, KeyedBore]
    roots: dict[str, float]
    module: float

    @property
    def failures(self) -> list[str]:
        """Each gear whose keyway leaves too thin a rim under the teeth, with the numbers."""
        return [text for name, bore in self.bores.items()
                for text in rim_failures(f"{name.replace('_', ' ')} bore", self.roots[name], bore, self.module)]


def shaft_torques(toothed: ToothedTrain, loads: Kinetostatics) -> dict[str, np.ndarray]:
    """Torque (N m) on each keyed shaft over the loads' turns, by the train's rates (module docstring)."""
    train, turns = toothed.train, loads.turns
    rod_rate = train.relative_angle.evaluate(turns, 1)
    return {"sun": loads.planet_torque * rod_rate,
            "intermediate": loads.planet_torque * rod_rate / train.intermediate_turn.rate(turns),
            "planet": loads.planet_torque}


def design_shafts(spec: ShaftSpec, toothed: ToothedTrain, loads: Kinetostatics,
                  plate_thickness_mm: float | None = None) -> ShaftDesign:
    """Given diameters where ``spec`` has them, else by the peak torque; hinge pins given, else by the peak force
    at B, E and F on plates ``plate_thickness_mm`` thick (None: the default thickness); each gear's keyed bore on
    its mark."""
    shafts = {}
    for name, torque in shaft_torques(toothed, loads).items():
        peak = float(np.abs(torque).max())
        given = spec.diameters_mm.get(name)
        shafts[name] = Shaft(name, given if given is not None else diameter_for_torque(peak), peak,
                             "given" if given is not None else "by peak torque")
    pin = spec.diameters_mm.get("hinge")
    magnitudes = loads.hinge_magnitudes()
    force = float(max(magnitudes[hinge].max() for hinge in PINNED_HINGES))
    shafts["hinge"] = Shaft("hinge", diameter_for_pin(force, plate_thickness_mm) if pin is None else pin, None,
                            "by peak hinge force in shear and bearing" if pin is None else "given", force)
    roots = {gear.name.replace(" ", "_"): float(np.linalg.norm(gear.outline, axis=1).min()) for gear in toothed.gears}
    bores = {}
    for gear in gears_on_carrier(toothed.train, toothed.carrier_length):
        shaft = SHAFT_OF_GEAR[gear.name]
        bores[gear.name] = KeyedBore.for_shaft(shafts[shaft].diameter, gear.contact_direction, f"shafts.{shaft}_mm")
    return ShaftDesign(shafts, bores, roots, toothed.module)

"""The five-bar's loads (``fivebar.kinetostatics``) for report.json and report.md: the load used and the peaks."""
from __future__ import annotations

import numpy as np

from transplanter.fivebar.kinetostatics import HINGES, Kinetostatics
from transplanter.fivebar.load_spec import GRAVITY

#: How the report's signs read.
CONVENTIONS = ("quasi-static, frictionless hinges, a lossless train passing pure torques; carrier torque positive "
               "clockwise (the drive doing work), train torque on rod AF positive counterclockwise, force in BE "
               "positive in tension; a torque's or BE's peak is the value of largest magnitude, with its sign")


def load_json(loads: Kinetostatics) -> dict:
    """The ``load`` object of report.json: the load used, and each peak with the carrier turn where it occurs
    (N, N m, deg)."""
    load, peaks = loads.load, loads.peaks()
    applied = {"force_n": load.force_n.tolist()} if load.force_n is not None else {"resisting_n": load.resisting_n}
    report = {**applied, "masses_kg": dict(load.masses_kg), "gravity_m_s2": GRAVITY,
              "stroke_deg": np.degrees(loads.stroke).tolist(), "conventions": CONVENTIONS}
    for name, unit in (("carrier_torque", "nm"), ("planet_torque", "nm"), ("be_force", "n")):
        value, turn = peaks[name]
        report[f"{name}_peak_{unit}"], report[f"{name}_peak_at_deg"] = value, float(np.degrees(turn))
    report["hinge_force_peak_n"] = {name: peaks[name][0] for name in HINGES}
    report["hinge_force_peak_at_deg"] = {name: float(np.degrees(peaks[name][1])) for name in HINGES}
    return report


def load_markdown(loads: Kinetostatics) -> list[str]:
    """Lines of report.md: the load used and the peaks."""
    load, peaks = loads.load, loads.peaks()
    applied = (f"constant force {load.force_n.tolist()} N at P" if load.force_n is not None
               else f"{load.resisting_n:g} N at P against its velocity")
    masses = ", ".join(f"{link.replace('_', ' ')} {mass:g} kg" for link, mass in load.masses_kg.items() if mass)
    stroke = np.degrees(loads.stroke)

    def peak(name: str, unit: str, digits: int) -> str:
        value, turn = peaks[name]
        return f"{value:.{digits}f} {unit} at {np.degrees(turn):.1f} deg"

    return [f"- load: {applied} over the pushing stroke {stroke[0]:g}-{stroke[1]:g} deg; "
            + (f"link masses {masses}" if masses else "no link masses"),
            f"- carrier input torque peak {peak('carrier_torque', 'N m', 3)}; train torque on the rod peak "
            f"{peak('planet_torque', 'N m', 3)}",
            f"- force in BE peak {peak('be_force', 'N', 1)} (tension +)",
            "- hinge force peaks: " + ", ".join(f"{name} {peak(name, 'N', 1)}" for name in HINGES)]

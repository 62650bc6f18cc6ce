"""The five-bar's shafts and bores (``fivebar.shafts``) for report.json and report.md."""
from __future__ import annotations

from transplanter.fivebar.shafts import ShaftDesign
from transplanter.shafts.sizing import (
    GEAR_SIZE_FRACTION,
    PIN_BEARING_PRESSURE_MPA,
    PIN_SHEAR_STRESS_MPA,
    TORSION_STRESS_MPA,
    min_rim,
)


def shafts_json(design: ShaftDesign) -> dict:
    """The ``shafts`` object of report.json: each shaft's diameter, peak torque and rule, each gear's bore (mm)."""
    return {
        "shafts": {name: {"diameter_mm": shaft.diameter, "peak_torque_nm": shaft.peak_torque_nm, "rule": shaft.rule,
                          **({} if shaft.peak_force_n is None else {"peak_force_n": shaft.peak_force_n})}
                   for name, shaft in design.shafts.items()},
        "bores": {name: {"diameter_mm": bore.diameter, "key_width_mm": bore.key.width,
                         "key_height_mm": bore.key.height, "hub_keyway_depth_mm": bore.key.hub_depth,
                         "keyway_reach_mm": bore.reach, "root_radius_mm": design.roots[name],
                         "rim_mm": design.roots[name] - bore.reach}
                  for name, bore in design.bores.items()},
        "min_rim_mm": min_rim(design.module), "torsion_stress_mpa": TORSION_STRESS_MPA,
        "gear_size_fraction": GEAR_SIZE_FRACTION, "pin_shear_stress_mpa": PIN_SHEAR_STRESS_MPA,
        "pin_bearing_pressure_mpa": PIN_BEARING_PRESSURE_MPA,
    }


def shafts_markdown(design: ShaftDesign) -> list[str]:
    """Lines of report.md: the shafts, then each gear's bore and the rim left under its teeth."""
    lines = [f"- {'hinge pins' if name == 'hinge' else name + ' shaft'}: {shaft.diameter:g} mm ({shaft.rule}"
             + (f", {shaft.peak_torque_nm:.3f} N m at peak)" if shaft.peak_torque_nm is not None else
                f", {shaft.peak_force_n:.1f} N at peak)" if shaft.peak_force_n is not None else ")")
             for name, shaft in design.shafts.items()]
    lines += [f"- {name.replace('_', ' ')}: bore {bore.diameter:g} mm, key {bore.key.width:g} x {bore.key.height:g} "
              f"(DIN 6885-1), keyway to {bore.reach:.3f} mm, root {design.roots[name]:.3f} mm, rim "
              f"{design.roots[name] - bore.reach:.3f} mm (at least {min_rim(design.module):.3f})"
              for name, bore in design.bores.items()]
    return lines

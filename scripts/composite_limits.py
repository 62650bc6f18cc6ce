"""Measure how far composite (corner) teeth hold: the table "How far it holds" of docs/gear.md.

    python scripts/composite_limits.py [--workers 2]

The driver is the bundled example's focal ellipse (a = 30 mm, e = 0.3) closed by a chord; the chord's
span sets the corner turn. For each span, tooth count and corner pressure angle (the package's trials,
``CORNER_PRESSURE_TRIALS_DEG``), the pair is designed with that angle given and the mesh check's
transmission error printed in mm, or "refused" when the construction refuses it (an arch that would
stand above the tip over the corner). Every run is independent; the whole table takes a few minutes on two cores.
"""
from __future__ import annotations

import argparse
from concurrent.futures import ProcessPoolExecutor

from transplanter import gears
from transplanter.errors import TransplanterError
from transplanter.gears.composite_teeth import CORNER_PRESSURE_TRIALS_DEG

#: Ellipse arcs from -span to +span deg; the chord closes the rest. 150 is the bundled example.
SPANS_DEG = (150.0, 140.0, 130.0, 120.0)
TEETH = (28, 29, 30, 31, 32)


def problem(span: float, teeth: int, corner: float) -> dict:
    ellipse = {"kind": "ellipse", "phi_deg": [-span, span], "semi_major_axis": 30.0, "eccentricity": 0.3}
    chord = {"kind": "line", "phi_deg": [span, 360.0 - span]}
    return {"driver": {"family": "composite", "segments": [ellipse, chord]},
            "pair": {"module": 2.0, "teeth": teeth, "corner_pressure_angle_deg": corner}}


def measure(case: tuple[float, int, float]) -> tuple[tuple[float, int, float], str, dict | None]:
    """(case, cell text, None when refused else {corner turn in deg, overlap in mm, smallest contact ratio})."""
    span, teeth, corner = case
    try:
        report = gears.synthesize(gears.parse_problem(problem(span, teeth, corner), "<scan>")).to_json()
    except TransplanterError:
        return case, "refused", None
    mesh = report["mesh_check"]
    found = {"turn": max(abs(c["turn_deg"]) for c in report["cusps"]), "overlap": mesh["max_overlap_mm"],
             "contact": report["contact_ratio_min"]}
    return case, f"{mesh['transmission_error_mm']:.4f}" + ("" if mesh["passed"] else " F"), found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, default=2)
    args = parser.parse_args()
    cases = [(span, teeth, corner) for span in SPANS_DEG for teeth in TEETH for corner in CORNER_PRESSURE_TRIALS_DEG]
    with ProcessPoolExecutor(args.workers) as pool:
        cells = {case: (text, found) for case, text, found in pool.map(measure, cases)}
    print("transmission error (mm; F: the mesh check fails, tolerance 0.01 mm) by corner pressure angle")
    print("| corner turn | teeth | " + " | ".join(f"{a:g} deg" for a in CORNER_PRESSURE_TRIALS_DEG) + " |")
    print("|---|---|" + "---|" * len(CORNER_PRESSURE_TRIALS_DEG))
    for span in SPANS_DEG:
        turns = [found["turn"] for (s, _, _), (_, found) in cells.items() if s == span and found]
        label = f"{turns[0]:.1f} deg (-{span:g} to {span:g})" if turns else f"(-{span:g} to {span:g})"
        for teeth in TEETH:
            row = [cells[(span, teeth, corner)][0] for corner in CORNER_PRESSURE_TRIALS_DEG]
            print(f"| {label} | {teeth} | " + " | ".join(row) + " |")
            label = ""
        made = [found for (s, _, _), (_, found) in cells.items() if s == span and found]
        if made:
            print(f"|   | overlap {min(f['overlap'] for f in made):.4f}-{max(f['overlap'] for f in made):.4f} mm, "
                  f"smallest contact ratio {min(f['contact'] for f in made):.3f} | | | | | |")


if __name__ == "__main__":
    main()

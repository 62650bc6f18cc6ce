"""Time a 30-tooth composite pair (ellipse arc and chord, examples/gear_cusp_composite.toml) with all its checks.

    python bench/bench_cusp.py

Stages timed in this process: pitch curves and closure; composite teeth (two shaper runs, the corner
arches, the driven gear carved as polygons); the mesh check; the contact ratio along the cycle. The
baseline is the driven gear by the library's normal-bin envelope (``swept_teeth.mate_profile``) on the
same driver: its time, and its mesh check, which the polygon carving replaces at the driven corners.
Target: the whole pair with its checks under 10 s.
"""
from __future__ import annotations

import time
from pathlib import Path

from transplanter import gears
from transplanter.gears.mesh_check import check_mesh
from transplanter.gears.swept_teeth import mate_profile
from transplanter.gears.teeth import driven_table

ROOT = Path(__file__).resolve().parents[1]


def main() -> None:
    problem = gears.load_problem(ROOT / "examples/gear_cusp_composite.toml")
    start = time.perf_counter()
    result = gears.synthesize(problem)
    total = time.perf_counter() - start
    report = result.to_json()
    print(f"composite pair, {problem.teeth} teeth of module {problem.module:g}: {total:.2f} s in all "
          f"(stages: {', '.join(f'{k} {v:.2f} s' for k, v in result.timings_s.items())})")
    mesh = report["mesh_check"]
    print(f"  contact ratio min {report['contact_ratio_min']:.3f} at {report['contact_ratio_where']}; positions "
          f"without contact: {sum(len(v) for v in report['contact_lost_at_deg'].values())}")
    print(f"  mesh check: overlap {mesh['max_overlap_mm']:.4f} mm, "
          f"transmission error {mesh['transmission_error_mm']:.4f} mm "
          f"({mesh['transmission_error_deg']:.4f} deg), passed {mesh['passed']}")
    start = time.perf_counter()
    baseline = mate_profile(result.design, result.teeth.outlines[0], driven_table(result.design), problem.module)
    elapsed = time.perf_counter() - start
    check = check_mesh(result.design, (result.teeth.outlines[0], baseline), problem.module)
    print(f"baseline driven by normal bins (mate_profile): {elapsed:.2f} s; overlap {check.max_overlap_mm:.4f} mm, "
          f"transmission error {check.max_transmission_error_mm:.4f} mm, passed {check.passed}")


if __name__ == "__main__":
    main()

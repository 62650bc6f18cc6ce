"""Speed of the tolerance Monte Carlo of the main job's five-bar (gears and linkage) against a per-sample loop.

    python bench/bench_tolerance.py

Both close the same 10,000 seeded built mechanisms (every toleranced dimension drawn at once) at the key
poses, the return points and 120 turns, with the same formula (``fivebar.tolerance_model.built_motion``):

- Package: ``tolerance.monte_carlo``, the numpy backend over arrays of mechanisms, then the hard conditions.
- Baseline: a Python loop over the samples, each mechanism closed alone by the same numpy formula (the
  way a per-sample simulation is written), then the same conditions.

Printed: both times, their ratio, the largest difference of the motions (they must agree to rounding), and
the other parts of ``tolerance.analyse`` (the exact Jacobian, the allocation NLP). The target is 10,000
samples in under 5 s on the 2-core machine.
"""
from __future__ import annotations

import time
from pathlib import Path

import numpy as np
from best_time import best_time  # bench/ is the script's own folder

from transplanter import fivebar
from transplanter.tolerance import analyse
from transplanter.tolerance.dimensions import SEED
from transplanter.tolerance.monte_carlo import draw, monte_carlo

ROOT = Path(__file__).resolve().parents[1]
SAMPLES = 10_000


def main():
    problem = fivebar.load_problem(ROOT / "examples" / "vegetable_planting.toml")
    result = fivebar.synthesize(problem, tolerance=False)
    model = result.tolerance_model()
    package, sampled = best_time(lambda: monte_carlo(model, SAMPLES, SEED, "uniform"), 3)
    dimensions = draw(model, SAMPLES, SEED, "uniform")

    def loop():
        motion = np.stack([model.sampled(row[None])[0] for row in dimensions])
        return motion, model.conditions(motion, dimensions)

    baseline, (motion, _) = best_time(loop, 1)
    vectorised = np.concatenate([model.sampled(part) for part in np.array_split(dimensions, 20)])
    start = time.perf_counter()
    analysis = analyse(model)
    whole = time.perf_counter() - start
    print(f"Monte Carlo of {SAMPLES} built five-bars ({len(model.dimensions)} dimensions, "
          f"{motion.shape[2]} turns each)")
    print(f"  package (arrays):        {package:8.3f} s")
    print(f"  baseline (sample loop):  {baseline:8.3f} s")
    print(f"  ratio:                   {baseline / package:8.1f} x")
    print(f"  largest motion difference: {np.nanmax(np.abs(vectorised - motion)):.2e}")
    print(f"  violation fractions: {sampled.violation_fraction}")
    print(f"tolerance.analyse on the main job: {whole:.3f} s "
          + ", ".join(f"{name} {seconds:.3f} s" for name, seconds in analysis.timings_s.items()))


if __name__ == "__main__":
    main()

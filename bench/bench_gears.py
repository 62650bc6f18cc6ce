"""Design the same gear pair with transplanter and with ncgears, in one run.

    pip install ncgears   # only for this benchmark (Apache-2.0)
    python bench/bench_gears.py

The pair (issue 4): focal ellipses, e = 0.3, 30 teeth of module 2, pressure angle 20 deg.
Both packages scale the curve so the perimeter is pi m Z, solve the center distance for
closure and generate tooth outlines. Target: at least 10 times faster, center distances
agreeing to 1e-9 mm. The closed form (twice the scaled semi-major axis) is printed too.
"""
from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

from transplanter.gears.problem import load_problem  # noqa: E402
from transplanter.gears.synthesis import synthesize  # noqa: E402


def best_time(function, repeat):
    best, value = float("inf"), None
    for _ in range(repeat):
        start = time.perf_counter()
        value = function()
        best = min(best, time.perf_counter() - start)
    return best, value


def main():
    try:
        import ncgears
    except ImportError:
        sys.exit("bench_gears needs ncgears: pip install ncgears")
    problem = load_problem(ROOT / "examples/gear_ellipse.toml")
    synthesize(problem)
    ours, result = best_time(lambda: synthesize(problem), 5)
    semi_major = 30.0 * result.design.driver.scale
    with tempfile.TemporaryDirectory() as folder:
        # the same curve up to scale: ncgears scales it to a perimeter of pi m Z itself
        theirs, pair = best_time(lambda: ncgears.generate_from_centrode(
            "0.91/(1-0.3*cos(phi))", teeth=30, module=2.0, pressure_angle_deg=20.0,
            output_directory=folder, name="ellipse"), 2)
    a_ours, a_theirs = result.design.center_distance, float(pair.metadata["center_distance"])
    print(f"transplanter: {ours * 1e3:.1f} ms (pitch curves {result.timings_s['pitch_curves'] * 1e3:.1f} ms, "
          f"teeth {result.timings_s['teeth'] * 1e3:.1f} ms), center distance {a_ours:.12f} mm")
    print(f"ncgears:      {theirs * 1e3:.1f} ms, center distance {a_theirs:.12f} mm")
    print(f"closed form 2a: {2 * semi_major:.12f} mm")
    print(f"ratio {theirs / ours:.1f}x (target >= 10x); center distances differ by {abs(a_ours - a_theirs):.2e} mm "
          f"(target <= 1e-9)")


if __name__ == "__main__":
    main()

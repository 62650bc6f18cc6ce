"""Time the 30-tooth focal-ellipse gear pair against the same job with the previous self-intersection test.

    python bench/bench_gears.py

The pair: focal ellipses, e = 0.3, 30 teeth of module 2, pressure angle 20 deg. The
baseline runs the same ``synthesize`` in the same process with the tooth outlines checked by the
windowed pairwise segment test the package used before shapely, so the ratio is what
that change (and the profiling after it) bought. Target: under 0.15 s on a quiet machine, center
distance equal to the closed form (twice the scaled semi-major axis) to 1e-12 mm. With ncgears
installed (``pip install ncgears``, Apache-2.0) the same pair is also timed with it, best of the same
``RUNS`` as the package, both sides writing their files (the package its SVG/DXF outlines and report, without
the animation; ncgears its own outputs) into a temporary folder.
"""
from __future__ import annotations

import tempfile
from pathlib import Path
from unittest import mock

import numpy as np
from best_time import best_time  # bench/ is the script's own folder

from transplanter.gears import teeth
from transplanter.gears.problem import load_problem
from transplanter.gears.synthesis import synthesize

ROOT = Path(__file__).resolve().parents[1]
#: Runs of each side; the best is printed.
RUNS = 7


def windowed_self_intersections(outline: np.ndarray, window: int = 400) -> int:
    """The previous test: segments sorted by the polar angle of their midpoints, each tested against
    the next ``window`` in that order, boxes first, then the orientation test (numpy)."""
    a, b = outline, np.roll(outline, -1, axis=0)
    n = len(a)
    order = np.argsort(np.arctan2(*((a + b) / 2)[:, ::-1].T))
    i = np.repeat(order, min(window, n) - 1)
    j = order[(np.arange(n)[:, None] + np.arange(1, min(window, n))[None, :]).ravel() % n]
    low, high = np.minimum(a, b), np.maximum(a, b)
    overlap = np.all((low[i] <= high[j]) & (low[j] <= high[i]), axis=1)
    gap = np.abs(i - j)
    i, j = i[overlap & (gap > 1) & (gap < n - 1)], j[overlap & (gap > 1) & (gap < n - 1)]
    side = teeth._side
    crossing = ((side(a[i], b[i], a[j]) * side(a[i], b[i], b[j]) < 0)
                & (side(a[j], b[j], a[i]) * side(a[j], b[j], b[i]) < 0))
    return int(crossing.sum())



def main():
    problem = load_problem(ROOT / "examples/gear_ellipse.toml")
    synthesize(problem)
    print("baseline: the package's own synthesis with the windowed pairwise self-intersection test it used "
          "before shapely; then ncgears (a peer's non-circular gear generator) where installed")
    ours, result = best_time(lambda: synthesize(problem), RUNS)
    with mock.patch.object(teeth, "self_intersections", windowed_self_intersections):
        baseline, previous = best_time(lambda: synthesize(problem), RUNS)
    closed_form = 2 * 30.0 * result.design.driver.scale
    a = result.design.center_distance
    print(f"transplanter: {ours * 1e3:.1f} ms (pitch curves {result.timings_s['pitch_curves'] * 1e3:.1f} ms, "
          f"teeth {result.timings_s['teeth'] * 1e3:.1f} ms), self-intersections {result.teeth.self_intersections}")
    print(f"baseline (previous self-intersection test): {baseline * 1e3:.1f} ms, "
          f"self-intersections {previous.teeth.self_intersections}")
    print(f"ratio {baseline / ours:.2f}x; target under 150 ms")
    print(f"center distance {a:.12f} mm, closed form 2a {closed_form:.12f} mm, differ by {abs(a - closed_form):.1e} mm "
          f"(target <= 1e-12)")
    try:
        import ncgears
    except ImportError:
        print("ncgears not installed: no comparison with it")
        return
    with tempfile.TemporaryDirectory() as folder:
        written, _ = best_time(lambda: synthesize(problem).write_files(Path(folder), animation=False), RUNS)
    with tempfile.TemporaryDirectory() as folder:
        # the same curve up to scale: ncgears scales it to a perimeter of pi m Z itself
        theirs, pair = best_time(lambda: ncgears.generate_from_centrode(
            "0.91/(1-0.3*cos(phi))", teeth=30, module=2.0, pressure_angle_deg=20.0,
            output_directory=folder, name="ellipse"), RUNS)
    print(f"best of {RUNS} each, both writing their files: transplanter {written * 1e3:.1f} ms, ncgears "
          f"{theirs * 1e3:.1f} ms ({theirs / written:.1f}x ours), center distance "
          f"{float(pair.metadata['center_distance']):.12f} mm")


if __name__ == "__main__":
    main()

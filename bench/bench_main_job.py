"""The main job against a bare start-up, in fresh processes of one run.

    python bench/bench_main_job.py [--runs 3]

Each of ``--runs`` rounds (default 3) times the main job as the CLI runs it (``transplanter fivebar
examples/vegetable_planting.toml --out DIR``: region, refinements, gears with their teeth, verification,
report, figures, drawings and the animation; ``--no-step``: the README's install has no ``cad`` extra, so its
main job writes no STEP, and the test command's install has it) and, right after, a bare fresh process that
does ``import numpy, casadi, matplotlib.pyplot`` and nothing else: the baseline is the least any command of the
package can take. Printed: the ratio main job / bare start-up per round, its min / median / max, the
absolute times, and the report's own wall times of the steps (target: at most 17x).
"""
from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from fresh_process import BARE_IMPORTS, bare_start_up, cli_run

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "vegetable_planting.toml"
TARGET = 17.0


def main(runs: int) -> None:
    print(f"baseline: a fresh `python -c \"{BARE_IMPORTS}\"`; package: `transplanter fivebar {EXAMPLE.name}` "
          "with every output file, in a fresh process")
    ratios, jobs, bares = [], [], []
    for round_ in range(runs):
        job, report = cli_run("fivebar", str(EXAMPLE), "--no-step")
        bare = bare_start_up()
        jobs.append(job)
        bares.append(bare)
        ratios.append(job / bare)
        steps = ", ".join(f"{name} {seconds:.2f} s" for name, seconds in report["timings_s"].items()
                          if isinstance(seconds, float))
        print(f"  round {round_ + 1}: main job {job:.2f} s, bare start-up {bare:.3f} s, ratio {ratios[-1]:.1f}x "
              f"({steps})")
    print(f"main job / bare start-up: min {min(ratios):.1f}x, median {np.median(ratios):.1f}x, max {max(ratios):.1f}x "
          f"(target at most {TARGET:g}x); main job min / median / max {min(jobs):.2f} / {np.median(jobs):.2f} / "
          f"{max(jobs):.2f} s; bare start-up {min(bares):.3f} / {np.median(bares):.3f} / {max(bares):.3f} s")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", type=int, default=3, help="rounds of the main job and the bare start-up")
    main(parser.parse_args().runs)

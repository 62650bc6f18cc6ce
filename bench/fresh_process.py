"""Wall time of one `transplanter` command in a fresh Python process (start-up included), and of a bare
start-up that imports what it imports (the yardstick of the main job's time)."""
from __future__ import annotations

import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def cli_run(*arguments: str) -> tuple[float, dict]:
    """Run ``transplanter <arguments> --out <temporary folder>``: the seconds it took and its report.json."""
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "transplanter", *arguments, "--out", out],
                       check=True, stdout=subprocess.DEVNULL)
        seconds = time.perf_counter() - start
        return seconds, json.loads((Path(out) / "report.json").read_text())


#: What every command's process imports before it does any work.
BARE_IMPORTS = "import numpy, casadi, matplotlib.pyplot"


def bare_start_up() -> float:
    """Seconds a fresh Python process takes to ``BARE_IMPORTS`` and exit."""
    start = time.perf_counter()
    subprocess.run([sys.executable, "-c", BARE_IMPORTS], check=True)
    return time.perf_counter() - start

"""Wall time of one `transplanter` command in a fresh Python process (start-up included)."""
from __future__ import annotations

import subprocess
import sys
import tempfile
import time


def cli_seconds(*arguments: str) -> float:
    """Run ``transplanter <arguments> --out <temporary folder>`` and return the seconds it took."""
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "transplanter", *arguments, "--out", out],
                       check=True, stdout=subprocess.DEVNULL)
        return time.perf_counter() - start

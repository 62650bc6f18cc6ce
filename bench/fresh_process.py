"""Wall time of one `transplanter` command in a fresh Python process (start-up included)."""
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

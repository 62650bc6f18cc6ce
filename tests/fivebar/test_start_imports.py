"""What a five-bar run imports before its design starts: not scipy.optimize (about 0.06 s), which only Table 5's
root of a seedling support takes, where it is found."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def test_a_five_bar_start_does_not_import_scipy_optimize():
    code = ("import sys\nfrom transplanter import cli, fivebar\n"
            "fivebar.load_problem('examples/vegetable_planting.toml')\nimport transplanter.fivebar.synthesis\n"
            "print('scipy.optimize' in sys.modules)\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert (run.returncode, run.stdout, run.stderr) == (0, "False\n", "")

"""IPOPT's OpenBLAS (casadi's own copy, loaded at the first nlpsol) runs one thread unless the user chose a
number: the solve layer sets OPENBLAS_NUM_THREADS when it is imported, before any solver exists, and never
overrides it. The thread count is asked of the loaded library itself (Linux: found in /proc/self/maps)."""
import os
import subprocess
import sys

import pytest

PROBE = """
import ctypes
import casadi as ca
import transplanter.solve.ipopt
x = ca.SX.sym("x")
ca.nlpsol("s", "ipopt", {"x": x, "f": x**2}, {"ipopt.print_level": 0, "print_time": False, "ipopt.sb": "yes"})
path = next(line.split()[-1] for line in open("/proc/self/maps") if "casadi-tp-openblas" in line)
print(ctypes.CDLL(path).openblas_get_num_threads())
"""


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads the loaded libraries from /proc/self/maps")
@pytest.mark.parametrize("given, expected", [(None, "1"), ("2", "2")])
def test_ipopts_openblas_runs_one_thread_unless_the_user_set_it(given, expected):
    environment = {key: value for key, value in os.environ.items() if key != "OPENBLAS_NUM_THREADS"}
    if given is not None:
        environment["OPENBLAS_NUM_THREADS"] = given
    run = subprocess.run([sys.executable, "-c", PROBE], capture_output=True, text=True, env=environment)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == expected

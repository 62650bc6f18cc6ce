"""The cores a process may use follow its CPU affinity (``taskset``, a container's cpuset), not the machine's
count."""
from __future__ import annotations

import os
import subprocess
import sys

import pytest

pytestmark = pytest.mark.skipif(not hasattr(os, "sched_setaffinity"), reason="the system keeps no CPU affinity")


@pytest.mark.parametrize("pinned", [1, 2])
def test_a_process_pinned_to_some_cores_may_use_only_those(pinned):
    allowed = sorted(os.sched_getaffinity(0))
    if len(allowed) < pinned:
        pytest.skip(f"this process may use {len(allowed)} core(s)")
    cores = set(allowed[:pinned])
    code = "from transplanter.side_process import usable_cores; print(usable_cores())"
    child = subprocess.run([sys.executable, "-c", code], preexec_fn=lambda: os.sched_setaffinity(0, cores),
                           capture_output=True, text=True, check=True)
    assert int(child.stdout) == pinned

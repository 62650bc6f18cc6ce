"""The Monte Carlo's chunks shared with a side process give what closing them all here gives, bit for bit, the
side process taking part."""
from __future__ import annotations

import dataclasses
import os
import time

import numpy as np
import pytest

from transplanter import side_process
from transplanter.tolerance.monte_carlo import CHUNK, monte_carlo

from .linear_model import linear_model


@pytest.mark.skipif(not side_process.FORKS, reason="a side process is forked on Linux only")
def test_shared_chunks_are_the_chunks_closed_here(monkeypatch, tmp_path):
    monkeypatch.setattr(side_process, "usable_cores", lambda: 2)
    model = linear_model(np.array([[1.0, 2.0, 0.5], [0.0, 1.0, -1.0], [0.3, 0.0, 1.0]]), [0.1, 0.2, 0.05])
    closed_by = tmp_path / "closed_by"
    closed_by.mkdir()

    def sampled(dimensions: np.ndarray) -> np.ndarray:
        """The model's motion, its process noted; 20 ms a chunk, so the side process has started (in far less) before
        this one, which takes chunks from the back until none is left, could have closed all forty."""
        (closed_by / str(os.getpid())).touch()
        time.sleep(0.02)
        return model.sampled(dimensions)

    shared_model = dataclasses.replace(model, sampled=sampled)
    samples = 40 * CHUNK
    shared = monte_carlo(shared_model, samples, 7, "uniform")
    with side_process.in_this_process():
        here = monte_carlo(model, samples, 7, "uniform")
    for field in ("position_3sigma_mm", "angle_3sigma_deg", "covariance"):
        assert np.array_equal(getattr(shared, field), getattr(here, field)), field
    assert shared.violation_fraction == here.violation_fraction and shared.not_closing == here.not_closing
    assert len(os.listdir(closed_by)) == 2      # this process (the nominal motion at least) and the side process

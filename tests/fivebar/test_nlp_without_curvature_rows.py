"""The design NLP built without the curvature rows (the NLP of the solves that hold no curvature) reaches the
design the full NLP reaches with those rows freed, and takes no curvature floor."""
from __future__ import annotations

import numpy as np
import pytest

from transplanter.fivebar.design_solver import DesignSolver
from transplanter.fivebar.nlp import CURVATURE_BLOCKS, GRID_POINTS
from transplanter.fivebar.region import solution_region


def test_the_nlp_without_curvature_rows_reaches_the_design_of_the_full_one_with_them_free(example_problem):
    solver = DesignSolver(example_problem)
    start = solution_region(example_problem).feasible[1]
    full, lean = solver.nlp_for(-1.0), solver.nlp_for(None)
    assert full is solver.nlp and not any(name in lean.layout.rows for name in CURVATURE_BLOCKS)
    assert full.layout.g.shape[0] - lean.layout.g.shape[0] == len(CURVATURE_BLOCKS) * (
        full.layout.rows[CURVATURE_BLOCKS[0]].size) and full.layout.rows[CURVATURE_BLOCKS[0]].size > GRID_POINTS

    poses, turns = start.key_poses(example_problem)
    values = full.start(start.mech, start.relative_angle, start.stroke, example_problem.return_points, poses, turns)
    freed = solver.solver.solve(values, full.bounds(0, None, float(values["least_curvature"])),
                                full.parameters(float(start.mech.branch), np.empty(0)))
    design = solver.solve(start, curvature_floor=None)
    assert design.objective == pytest.approx(freed.objective, rel=1e-8, abs=1e-10)
    lengths = slice(0, full.layout.variables["relative_angle_start"].start)
    assert np.abs(design.solved.x[lengths] - freed.x[lengths]).max() < 1e-6
    with pytest.raises(ValueError, match="without the curvature rows"):
        lean.bounds(0, -1.0, 0.0)

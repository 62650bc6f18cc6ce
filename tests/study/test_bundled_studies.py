"""The bundled example studies: each loads, has the cases the issue asks of an example (at least 8, each a
problem its command accepts) and names two objectives for a Pareto front. Running them end to end takes
minutes (a five-bar case is a whole synthesis): `transplanter study examples/<file> --out DIR`."""
from __future__ import annotations

import numpy as np
import pytest

from tests.study.studies import EXAMPLES
from transplanter import fivebar
from transplanter.study import load_study, study_cases

STUDIES = sorted(EXAMPLES.glob("*study*.toml"))


def test_both_five_bar_studies_are_bundled():
    assert {path.name for path in STUDIES} >= {"vegetable_planting_study.toml",
                                                "vegetable_planting_variants_study.toml"}


@pytest.mark.parametrize("path", STUDIES, ids=lambda path: path.stem)
def test_a_bundled_study_has_eight_cases_or_more_each_a_problem_its_command_accepts(path):
    spec = load_study(path)
    cases = study_cases(spec)
    assert len(cases) >= 8 and len({case.case_id for case in cases}) == len(cases)
    assert len(spec.objectives) == 2
    for case in cases:
        fivebar.parse_problem(case.problem, f"{path.name} case {case.case_id}")


def test_the_variants_stay_within_their_small_bands_around_the_working_example():
    """Each case moves the working example's key poses by at most 1 mm and 1 deg, its carrier turns by at most
    0.6 deg."""
    spec = load_study(EXAMPLES / "vegetable_planting_variants_study.toml")
    base = fivebar.load_problem(EXAMPLES / "vegetable_planting.toml")
    for case in study_cases(spec):
        moved = fivebar.parse_problem(case.problem, case.case_id)
        assert np.abs(moved.poses[:, :2] - base.poses[:, :2]).max() <= 1.0 + 1e-9
        assert np.degrees(np.abs(moved.poses[:, 2] - base.poses[:, 2])).max() <= 1.0 + 1e-9
        assert np.degrees(np.abs(moved.carrier_turns - base.carrier_turns)).max() <= 0.6 + 1e-9

"""The cases of a study: each a set of values of the varied fields, named by a hash of its inputs."""
from __future__ import annotations

import hashlib
import itertools
import json
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.stats import qmc

from transplanter.study.field_paths import replaced
from transplanter.study.spec import StudySpec


@dataclass(frozen=True)
class Case:
    """One case: its id, the values of the varied fields and the problem file's content with them."""

    case_id: str
    values: dict[str, Any]
    problem: dict


def inputs_hash(command: str, document: Any, length: int = 16) -> str:
    """The first ``length`` hex digits of the sha256 of the command and ``document`` as canonical JSON (keys
    sorted): equal inputs give equal hashes, in any process and on any machine."""
    text = json.dumps({"command": command, "input": document}, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:length]


def _band_samples(spec: StudySpec) -> list[dict[str, float]]:
    """The seeded samples over the bands (Latin hypercube or scrambled Sobol), scaled to each band."""
    banded = [v for v in spec.varied if v.band]
    if not banded:
        return [{}]
    if spec.sampling == "sobol":
        sampler: qmc.QMCEngine = qmc.Sobol(len(banded), scramble=True, seed=spec.seed)
    else:
        sampler = qmc.LatinHypercube(len(banded), seed=spec.seed)
    unit = sampler.random(spec.samples)
    lows, highs = np.array([v.band for v in banded]).T
    points = qmc.scale(unit, lows, highs)
    return [{v.field: float(x) for v, x in zip(banded, row, strict=True)} for row in points]


def study_cases(spec: StudySpec) -> list[Case]:
    """Every case of ``spec``: the product of the lists and ranges, times the band samples; a case that
    repeats another's inputs is kept once."""
    listed = [v for v in spec.varied if not v.band]
    cases: dict[str, Case] = {}
    for combination in itertools.product(*(v.values for v in listed)):
        for sample in _band_samples(spec):
            given = {v.field: value for v, value in zip(listed, combination, strict=True)} | sample
            values = {name: given[name] for name in spec.fields}
            problem = replaced(spec.problem, values)
            case_id = inputs_hash(spec.command, problem)
            cases.setdefault(case_id, Case(case_id, values, problem))
    return list(cases.values())

"""Design studies: many cases of one design command, on local worker processes or a Dask cluster, each result
written as it finishes (``transplanter study STUDY.toml --out DIR``).

Public API: ``load_study`` / ``parse_study`` (TOML file or dict) -> ``StudySpec``; ``study_cases(spec)`` ->
the ``Case`` list, each named by a hash of its inputs; ``run(spec, out, executor=...)`` -> ``StudyOutcome``,
on any ``concurrent.futures.Executor`` or a ``distributed.Client``.
"""
from transplanter.lazy_exports import lazy_exports

__all__ = ["Case", "StudyOutcome", "StudySpec", "load_study", "parse_study", "run", "study_cases"]
__getattr__, __dir__ = lazy_exports(__name__, {
    "Case": "cases",
    "study_cases": "cases",
    "StudyOutcome": "runner",
    "run": "runner",
    "StudySpec": "spec",
    "load_study": "spec",
    "parse_study": "spec",
})

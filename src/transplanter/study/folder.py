"""A study's output folder: results are added as the cases finish, so it is checked, not staged.

The folder holds study.json (what study it is: a hash of everything that defines its table), cases.csv,
cases/<case_id>/report.json, and at the end report.md, report.json and the figures. It must be new, empty,
or hold the same study (continued with ``resume``); a folder of anything else is refused.
"""
from __future__ import annotations

import json
from dataclasses import asdict
from pathlib import Path

from transplanter.errors import ProblemError
from transplanter.output_folder import report_json, staged_file
from transplanter.study.cases import inputs_hash
from transplanter.study.spec import StudySpec

#: The file that names the study a folder holds.
STUDY_FILE = "study.json"


def study_hash(spec: StudySpec) -> str:
    """A hash of what defines the study's table: the command, the problem, the varied fields and their values or
    bands, the sampling and the collected quantities (not the title nor the executor)."""
    return inputs_hash(spec.command, {"problem": spec.problem, "varied": [asdict(v) for v in spec.varied],
                                      "sampling": [spec.sampling, spec.samples, spec.seed],
                                      "collect": list(spec.collect)})


def prepare_folder(out: str | Path, spec: StudySpec, resume: bool) -> Path:
    """The output folder, made if missing and marked with study.json; ProblemError for a file, a folder of
    other files or of another study, or a folder of this study without ``resume``."""
    folder, expected = Path(out), study_hash(spec)
    if folder.exists() and not folder.is_dir():
        raise ProblemError(f"--out = {out}: a file is there; expected a folder for the study's results")
    present = sorted(path.name for path in folder.iterdir()) if folder.is_dir() else []
    if present:
        try:
            held = json.loads((folder / STUDY_FILE).read_text()).get("study")
        except (OSError, ValueError, AttributeError):
            raise ProblemError(f"--out = {out}: the folder holds files that are not a study's results "
                               f"({', '.join(present[:3])}{', ...' if len(present) > 3 else ''}); expected a new or "
                               "empty folder, or one of this study") from None
        if held != expected:
            raise ProblemError(f"--out = {out}: the folder holds the results of another study ({held}; this one is "
                               f"{expected}); expected a new or empty folder, or one of this study")
        if not resume:
            raise ProblemError(f"--out = {out}: the folder holds results of this study; expected --resume to run "
                               "the cases it lacks, or a new folder")
    (folder / "cases").mkdir(parents=True, exist_ok=True)
    if not present:
        with staged_file(folder / STUDY_FILE) as partial:
            partial.write_text(report_json({"study": expected, "title": spec.title, "source": spec.source,
                                            "command": spec.command, "problem": spec.problem_file,
                                            "fields": list(spec.fields), "collect": list(spec.collect)}) + "\n")
    return folder

"""``transplanter study STUDY.toml --out DIR``: load the study, run it, say what it left; the exit code is 0
when every case ran to its command's verdict, 1 when some timed out, crashed or hit an unexpected error."""
from __future__ import annotations

import sys

from transplanter.study.runner import run
from transplanter.study.spec import load_study, replace_scheduler


def run_study(args, shown: bool) -> int:
    """Run the study of ``args`` (file, study_out, resume, scheduler), the progress bar on stderr when ``shown``."""
    spec = replace_scheduler(load_study(args.file), args.scheduler)
    outcome = run(spec, args.study_out, resume=args.resume, show_progress=shown)
    statuses: dict[str, int] = {}
    for row in outcome.rows:
        statuses[row["status"]] = statuses.get(row["status"], 0) + 1
    sys.stdout.write(f"{spec.title}: {len(outcome.rows)} cases ({outcome.ran} run now): "
                     + ", ".join(f"{count} {status}" for status, count in statuses.items())
                     + f"; wrote {args.study_out}/: report.md, report.json, cases.csv, cases/<case_id>/report.json\n")
    unfinished = outcome.unfinished
    if unfinished:
        print(f"transplanter: failed: {len(unfinished)} cases did not run to a verdict ("
              + ", ".join(sorted({row['status'] for row in unfinished})) + f"); {args.study_out}/report.md lists them",
              file=sys.stderr)
        return 1
    return 0

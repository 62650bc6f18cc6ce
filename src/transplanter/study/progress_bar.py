"""The study's progress bar on stderr (tqdm): cases done of all, how many failed, the rate and the time left."""
from __future__ import annotations

import sys

from tqdm import tqdm

from transplanter.study.case_run import PASSED


class ProgressBar:
    """A bar over ``total`` cases of which ``done`` were finished before; silent unless ``shown``."""

    def __init__(self, total: int, done: int, shown: bool):
        self.failed = 0
        self.bar = tqdm(total=total, initial=done, unit="case", file=sys.stderr, disable=not shown,
                        desc="transplanter: study", dynamic_ncols=True, smoothing=0.1)

    def advance(self, status: str):
        """One more case finished, with ``status``."""
        self.failed += status != PASSED
        self.bar.set_postfix_str(f"{self.failed} not passed", refresh=False)
        self.bar.update()

    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(self, *exc):
        self.bar.close()

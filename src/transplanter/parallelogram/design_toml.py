"""design.toml of a designed onion transplanter: the eight variables of the design its gears, drawings and
trajectory are made for (``ParallelogramResult.final``), named as in the report's design table, so that
``transplanter parallelogram PROBLEM --design design.toml`` evaluates the same design."""
from __future__ import annotations

from pathlib import Path

from transplanter.design_file import write_design_file
from transplanter.parallelogram.report import variables_json
from transplanter.parallelogram.result import ParallelogramResult


def write_design(result: ParallelogramResult, folder: str | Path) -> Path:
    """``folder/design.toml`` of ``result``; the path written."""
    problem = result.problem
    return write_design_file(
        folder, "The onion transplanter designed by transplanter parallelogram",
        f"Designed for {problem.title or problem.source}. Evaluate with: transplanter parallelogram "
        f"{problem.source} --design design.toml", {"design": variables_json(result.final)})

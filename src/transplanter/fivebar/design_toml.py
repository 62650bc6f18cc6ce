"""design.toml of a designed five-bar: the fields of its design table that ``load_design`` reads (the report's
names), its motion rho(c) and, for a problem with key-pose bands, the key poses it chose, so that
``transplanter fivebar PROBLEM --design design.toml`` judges the same mechanism, moved by the same relative
angle at the same key poses, and reproduces the run's report."""
from __future__ import annotations

from pathlib import Path

from transplanter.design_file import write_design_file
from transplanter.fivebar.evaluation import DESIGN_FIELDS
from transplanter.fivebar.key_pose_bands import QUANTITIES
from transplanter.fivebar.report import design_json, pose_rows_json, relative_angle_json
from transplanter.fivebar.result import FiveBarResult


def write_design(result: FiveBarResult, folder: str | Path) -> Path:
    """``folder/design.toml`` of ``result``; the path written."""
    problem, design = result.problem, result.design
    table = design_json(design.mech, problem.poses[0])
    rows = pose_rows_json(problem.poses, problem.carrier_turns)
    chosen = {"key_poses": {quantity: [row[quantity] for row in rows] for quantity in QUANTITIES}} \
        if result.pose_bands is not None else {}
    return write_design_file(
        folder, f"The five-bar designed for {problem.title or problem.source}",
        f"Written by transplanter fivebar. Evaluate with: transplanter fivebar {problem.source} --design design.toml",
        {"design": {key: table[key] for key in DESIGN_FIELDS},
         "relative_angle": relative_angle_json(design.relative_angle, design.stroke.carrier_turns), **chosen})

"""A dyad synthesis as JSON (report.json), a text table (terminal) and Markdown (report file)."""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from transplanter.burmester.result import Synthesis
from transplanter.geometry.dyad import Dyad

#: Rows a text or Markdown table shows at most; JSON always has every dyad.
TABLE_ROWS = 24


def dyad_json(dyad: Dyad) -> dict:
    """Fixed pivot ``center`` and moving pivot ``circle`` in pose 1 (mm), length (mm) and residuals."""
    return {"center": dyad.center.tolist(), "circle": dyad.circle.tolist(), "length": dyad.length,
            "max_residual": dyad.max_residual, "max_residual_mm": dyad.max_residual_mm,
            "residuals_mm": dyad.residuals_mm.tolist()}


def synthesis_json(result: Synthesis) -> dict:
    """The report as plain JSON types (lengths in mm, angles in degrees): the content of report.json."""
    problem = result.problem
    dyads = result.dyads + result.circle_curve_dyads
    labels = problem.labels or [""] * len(problem.poses)
    out = {
        "source": problem.source,
        "title": problem.title,
        "method": result.method,
        "pose_count": len(problem.poses),
        "poses": [{"label": label, "x": p[0], "y": p[1], "angle_deg": float(np.degrees(p[2]))}
                  for label, p in zip(labels, problem.poses.tolist(), strict=True)],
        "relative": None if problem.link is None else {
            "pivot": problem.link.pivot.tolist(), "phases_deg": np.degrees(problem.link.phases).tolist()},
        "pose_scale_mm": dyads[0].scale if dyads else None,
        "radius_mm": result.radius_mm,
        "max_residual": max((d.max_residual for d in dyads), default=None),
        "dyads": [dyad_json(d) for d in result.dyads],
    }
    if result.center_curve is not None:
        out["circle_curve_dyads"] = [dyad_json(d) for d in result.circle_curve_dyads]
    if result.rms_mm:
        out["rms_mm"] = result.rms_mm
    return out


def _shown(dyads: list[Dyad]) -> list[tuple[int, Dyad]]:
    if len(dyads) <= TABLE_ROWS:
        return list(enumerate(dyads))
    picks = np.linspace(0, len(dyads) - 1, TABLE_ROWS).astype(int)
    return [(int(k), dyads[k]) for k in picks]


def _rows(result: Synthesis) -> list[list[str]]:
    return [[str(k + 1), f"{d.center[0]:.4f}", f"{d.center[1]:.4f}", f"{d.circle[0]:.4f}", f"{d.circle[1]:.4f}",
             f"{d.length:.4f}", f"{d.max_residual:.1e}"] for k, d in _shown(result.dyads)]


_HEADER = ["#", "center x", "center y", "circle x", "circle y", "length", "max residual"]


def _summary(result: Synthesis) -> list[str]:
    problem = result.problem
    lines = [f"{problem.title or problem.source}", f"method: {result.method}",
             f"poses: {len(problem.poses)}" + ("" if problem.link is None else
                                               f", relative to a link turning about {problem.link.pivot.tolist()} mm")]
    dyads = result.dyads
    if not dyads:
        lines.append("no real dyad meets these poses" if len(problem.poses) == 5 else "no dyad found")
    else:
        worst = max(d.max_residual for d in dyads + result.circle_curve_dyads)
        lines.append(f"dyads: {len(dyads)}; largest residual of eq (1): {worst:.1e} of the pose scale "
                     f"({dyads[0].scale:.3f} mm), by forward kinematics")
    if result.rms_mm:
        lines.append("least squares: RMS length error " + ", ".join(f"{v:.2e}" for v in result.rms_mm) + " mm")
    if len(dyads) > TABLE_ROWS:
        lines.append(f"table: {TABLE_ROWS} of {len(dyads)} dyads, evenly along the center-point curve (--json for all)")
    lines.append("center = fixed pivot" + (" on the link" if problem.link is not None else "")
                 + " and circle = moving pivot, both in pose 1 (mm); residual relative to the pose scale")
    return lines


def to_text(result: Synthesis) -> str:
    """The summary and the table on a terminal."""
    rows = [_HEADER] + _rows(result)
    widths = [max(len(r[c]) for r in rows) for c in range(len(_HEADER))]
    table = ["  ".join(cell.rjust(w) for cell, w in zip(r, widths, strict=True)) for r in rows]
    return "\n".join(_summary(result) + [""] + table) + "\n"


def to_markdown(result: Synthesis, files: Sequence[str] = ()) -> str:
    """report.md: the summary and the table, and the figure when ``files`` holds it."""
    summary = _summary(result)
    lines = [f"# {summary[0]}", ""] + [f"- {line}" for line in summary[1:]] + [""]
    lines += ["| " + " | ".join(_HEADER) + " |", "|" + "---|" * len(_HEADER)]
    lines += ["| " + " | ".join(r) + " |" for r in _rows(result)]
    for figure in (name for name in files if name.endswith(".png")):
        lines += ["", f"![poses, curves and dyads]({figure})"]
    return "\n".join(lines) + "\n"

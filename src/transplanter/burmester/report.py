"""A dyad synthesis as a text table (terminal) and Markdown (report file); its JSON is ``Synthesis.to_json``."""
from __future__ import annotations

import numpy as np

from transplanter.burmester.result import Synthesis
from transplanter.geometry.dyad import Dyad

#: Rows a text or Markdown table shows at most; JSON always has every dyad.
TABLE_ROWS = 24


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
    rows = [_HEADER] + _rows(result)
    widths = [max(len(r[c]) for r in rows) for c in range(len(_HEADER))]
    table = ["  ".join(cell.rjust(w) for cell, w in zip(r, widths)) for r in rows]
    return "\n".join(_summary(result) + [""] + table) + "\n"


def to_markdown(result: Synthesis, figure: str | None) -> str:
    summary = _summary(result)
    lines = [f"# {summary[0]}", ""] + [f"- {line}" for line in summary[1:]] + [""]
    lines += ["| " + " | ".join(_HEADER) + " |", "|" + "---|" * len(_HEADER)]
    lines += ["| " + " | ".join(r) + " |" for r in _rows(result)]
    if figure:
        lines += ["", f"![poses, curves and dyads]({figure})"]
    return "\n".join(lines) + "\n"

"""The tolerance analysis as JSON (the ``tolerance`` section of report.json) and as a report.md section."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from transplanter.tolerance.analysis import AGREEMENT

if TYPE_CHECKING:
    from transplanter.tolerance.analysis import ToleranceAnalysis


def _finite(value: float) -> float | None:
    return float(value) if np.isfinite(value) else None


def tolerance_json(analysis: ToleranceAnalysis) -> dict:
    """``dimensions``, ``key_poses``, ``sensitivity``, ``violation_fraction``, ``allocation`` and how they were
    obtained (mm, deg)."""
    model, settings, mc = analysis.model, analysis.settings, analysis.monte_carlo
    labels = model.key_labels
    jacobian = analysis.jacobian
    position_parts, angle_parts = analysis.disagreement()
    key_poses = [{"label": label,
                  "first_order_3sigma_mm": _finite(analysis.first_order_3sigma_mm[i]),
                  "monte_carlo_3sigma_mm": _finite(mc.position_3sigma_mm[i]),
                  "first_order_3sigma_deg": _finite(analysis.first_order_3sigma_deg[i]),
                  "monte_carlo_3sigma_deg": _finite(mc.angle_3sigma_deg[i]),
                  "worst_case_mm": _finite(analysis.worst_case_mm[i]),
                  "worst_case_deg": _finite(analysis.worst_case_deg[i]),
                  "first_order_holds": bool(position_parts[i] <= AGREEMENT and angle_parts[i] <= AGREEMENT)}
                 for i, label in enumerate(labels)]
    sensitivity = {name: {label: [float(jacobian[0, i, j]), float(jacobian[1, i, j]),
                                  float(np.degrees(jacobian[2, i, j]))] for i, label in enumerate(labels)}
                   for j, name in enumerate(model.names)}
    allocation = analysis.allocation
    allocated = None if allocation is None else {
        "pose_position_mm": settings.pose_position_mm, "pose_angle_deg": settings.pose_angle_deg,
        "tolerances": dict(zip(model.names, allocation.tolerances.tolist(), strict=True)),
        "first_order_3sigma_mm": allocation.position_3sigma_mm.tolist(),
        "first_order_3sigma_deg": allocation.angle_3sigma_deg.tolist(),
        "binding": list(allocation.binding), "status": allocation.status, "iterations": allocation.iterations}
    return {
        "distribution": settings.distribution, "samples": settings.samples, "seed": settings.seed,
        "dimensions": [{"name": d.name, "nominal": d.nominal, "tolerance": d.tolerance, "unit": d.unit,
                        "source": d.what} for d in model.dimensions],
        "key_poses": key_poses,
        "sensitivity": sensitivity,
        "variance_share": {name: dict(zip(labels, analysis.position_shares[:, j].tolist(), strict=True))
                           for j, name in enumerate(model.names)},
        "largest_contributions": [{"name": name, "mean_share": share}
                                  for name, share in analysis.largest_contributions()],
        "violation_fraction": mc.violation_fraction,
        "not_closing_samples": mc.not_closing,
        "trajectory_first_order_3sigma_mm_max": _finite(np.max(analysis.first_order_3sigma_mm[model.whole_turn])),
        "trajectory_monte_carlo_3sigma_mm_max": _finite(np.max(mc.position_3sigma_mm[model.whole_turn])),
        "allocation": allocated,
        "allocation_note": analysis.allocation_note or None,
        "timings_s": analysis.timings_s,
    }


def _fraction(value: float) -> str:
    return f"{100 * value:.2f} %"


def tolerance_markdown(analysis: ToleranceAnalysis) -> list[str]:
    """report.md lines: the key poses' bands, what matters most, the margins and the allocation."""
    model, settings, mc = analysis.model, analysis.settings, analysis.monte_carlo
    labels, k = model.key_labels, analysis.key_count
    position_parts, angle_parts = analysis.disagreement()
    lines = ["## Tolerances (the built mechanism)", "",
             f"{len(model.dimensions)} toleranced dimensions ({settings.distribution} within their limits); first "
             f"order from the exact Jacobian, Monte Carlo of {settings.samples} built mechanisms "
             f"(seed {settings.seed}).",
             "", "| | " + " | ".join(labels) + " |", "|---" * (k + 1) + "|"]
    point, angle = model.point, model.angle
    rows = ((f"{point} 3σ, first order (mm)", analysis.first_order_3sigma_mm),
            (f"{point} 3σ, Monte Carlo (mm)", mc.position_3sigma_mm),
            (f"{point} worst case (mm)", analysis.worst_case_mm),
            (f"{angle} 3σ, first order (deg)", analysis.first_order_3sigma_deg),
            (f"{angle} 3σ, Monte Carlo (deg)", mc.angle_3sigma_deg),
            (f"{angle} worst case (deg)", analysis.worst_case_deg))
    lines += [f"| {name} | " + " | ".join(f"{v:.4f}" for v in values[:k]) + " |" for name, values in rows]
    broken = [f"{label} {what} ({100 * part:.0f} % off)" for what, parts in ((point, position_parts),
                                                                         (angle, angle_parts))
              for label, part in zip(labels, parts, strict=True) if not part <= AGREEMENT]
    agreement = f"{100 * AGREEMENT:.0f} %"
    lines += ["", f"First order and Monte Carlo agree within {agreement} at every key pose." if not broken
              else f"First order breaks (Monte Carlo more than {agreement} off) at: {', '.join(broken)}.", ""]
    lines += ["| dimension | nominal | tolerance (±) | unit | from |", "|---|---|---|---|---|"]
    lines += [f"| {d.name} | {d.nominal:.6g} | {d.tolerance:.4g} | {d.unit} | {d.what} |" for d in model.dimensions]
    lines += ["", "Dimensions that matter most (mean share of the key poses' position variance): "
              + ", ".join(f"{name} {100 * share:.0f} %" for name, share in analysis.largest_contributions()) + ".", ""]
    lines += ["| hard condition | built mechanisms that violate it |", "|---|---|"]
    lines += [f"| {name} | {_fraction(value)} |" for name, value in mc.violation_fraction.items()]
    allocation = analysis.allocation
    lines += [""]
    if allocation is None:
        lines += [f"Tolerance allocation: {analysis.allocation_note}.", ""]
    else:
        lines += [f"Tolerance allocation for {point} within {settings.pose_position_mm:g} mm and the {angle} within "
                  f"{settings.pose_angle_deg:g} deg (3σ) at every key pose (binding: "
                  f"{', '.join(allocation.binding) or 'none, every tolerance at its loosest'}):", "",
                  "| dimension | tolerance now | loosest allowed | unit |", "|---|---|---|---|"]
        lines += [f"| {d.name} | {d.tolerance:.4g} | {t:.4g} | {d.unit} |"
                  for d, t in zip(model.dimensions, allocation.tolerances, strict=True)]
    return [*lines, ""]

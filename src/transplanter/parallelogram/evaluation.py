"""One design evaluated (``--design``), and the onion-transplanter paper's published optimum evaluated both ways.

A design file holds the eight variables ([design], as in a problem file), optionally the values
the paper printed for its gear ([printed]: m12, center_distance, teeth) and the figures it
reports ([published]: depth_mm, vx_release_mm_s, vertical_range_mm, spacing_mm). With [printed],
the design is evaluated with the curve as printed and with the corrected closed curve (m12 from
eq 2, closing center distance), each under the problem's conventions and under eq (17) read
literally (``PRINTED_EQ17``).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from transplanter.parallelogram.gear_checks import gear_margins, undercut_limit
from transplanter.parallelogram.kinematics import mechanisms
from transplanter.parallelogram.problem import (
    PRINTED_EQ17,
    Conventions,
    ParallelogramProblem,
    check_design,
    check_gear_figures,
    read_design,
    read_printed,
    read_published,
)
from transplanter.parallelogram.trajectory import measure
from transplanter.toml_fields import LONGEST_TITLE, ClassFields, FieldReader, read_toml

#: Samples per turn of the independent evaluation (finer than the search's grid).
EVALUATION_SAMPLES = 8192


@dataclass(frozen=True)
class DesignFile:
    """A design to evaluate: the eight variables (mm, rad), printed gear values and published figures."""

    design: dict
    printed: dict = field(default_factory=dict)      # m12, center_distance (mm), teeth
    published: dict = field(default_factory=dict)    # PUBLISHED_FIELDS -> value
    source: str = "<dict>"
    title: str = ""

    def __post_init__(self):
        check = ClassFields(self)
        check_design(check, self.design)
        check_gear_figures(check, self.printed, self.published)
        check.text("source", "title")


def parse_design(data: dict, source: str = "<dict>") -> DesignFile:
    """Validate a design file given as a dict (mm, degrees)."""
    read = FieldReader(source)
    read.keys(data, {"title", "description", "design", "printed", "published"}, "")
    if "design" not in data:
        read.fail("design", None, "a [design] table with the eight variables")
    design = read_design(read, data["design"])
    return DesignFile(design, read_printed(read, data.get("printed", {}), design),
                      read_published(read, data.get("published", {})), source,
                      read.text(data, "title", "", LONGEST_TITLE))


def load_design(path: str | Path) -> DesignFile:
    return parse_design(read_toml(path), str(path))


def problem_design(problem: ParallelogramProblem) -> DesignFile:
    """The problem's own [design] with its [printed] and [published] tables, as a design file."""
    return DesignFile(problem.design, problem.printed, problem.published, problem.source, problem.title)


@dataclass(frozen=True)
class Evaluation:
    """One design under one gear reading and one set of conventions (mm, mm/s, s, deg in JSON)."""

    label: str
    conventions: str
    m12: float
    center_distance: float
    driven_turn_deg: float
    depth: float
    vx_release: float
    ax_release: float
    vertical_range: float
    spacing: float
    planting_time: float
    window_cut: bool
    convex: bool
    undercut_free: bool
    min_curvature_radius: tuple[float, float]


def evaluate(problem: ParallelogramProblem, design: dict, label: str = "closed", m12=None, center_distance=None,
             conventions: Conventions | None = None, conventions_name: str = "file") -> Evaluation:
    """Measures of one design (mm, rad) on a fine grid; ``m12`` / ``center_distance`` replace eq (2) / closure."""
    if conventions is not None:
        problem = dataclasses.replace(problem, conventions=conventions)
    mech = mechanisms(problem, design, m12=m12, center_distance=center_distance)
    m = measure(mech, problem.depth_window, EVALUATION_SAMPLES)
    gear = gear_margins(mech.m11, mech.m12, mech.amplitude, mech.base_radius, mech.center_distance)
    limit = undercut_limit(problem.module, problem.pressure_angle)
    rho = (float(gear.driver_curvature[0]), float(gear.driven_curvature[0]))
    convex = bool(gear.driver_convexity[0] > 0 and gear.driven_convexity[0] > 0)
    return Evaluation(label, conventions_name, float(mech.m12[0]), float(mech.center_distance[0]),
                      float(np.degrees(mech.driven_turn[0])), float(m.depth[0]), float(m.vx_release[0]),
                      float(m.ax_release[0]), float(m.vertical_range[0]), float(m.spacing[0]),
                      float(m.planting_time[0]), bool(m.window_cut[0]), convex, bool(convex and min(rho) >= limit), rho)


def evaluate_published(problem: ParallelogramProblem, given: DesignFile) -> list[Evaluation]:
    """The design with the corrected closed curve and, when [printed] is given, the curve as printed;
    each under the problem's conventions and under eq (17) read literally."""
    curves = [("closed", None, None)]
    if given.printed.get("m12") is not None or given.printed.get("center_distance") is not None:
        curves.insert(0, ("as printed", given.printed.get("m12"), given.printed.get("center_distance")))
    rows = []
    for conventions, name in ((None, "file"), (PRINTED_EQ17, "eq (17) literal")):
        for label, m12, a in curves:
            rows.append(evaluate(problem, given.design, label, m12, a, conventions, name))
    return rows

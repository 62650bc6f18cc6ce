"""A study file: one problem file of a design command, the fields to vary, the quantities to collect.

Schema (TOML)::

    title = "..."                       # optional
    command = "fivebar"                 # any design command: burmester, gear, fivebar, reverse, cam, ...
    problem = "vegetable_planting.toml" # its problem file, relative to the study file
    collect = ["design.carrier_length_OA", "transmission_angle_min_deg"]   # report.json paths

    [[vary]]                            # one table per field, addressed by its TOML path
    field = "key_poses.2.angle_deg"
    values = [88.0, 90.0, 92.0]         # a list, or
    # range = [88.0, 92.0]              # low to high in steps of
    # step = 1.0
    # band = [88.0, 92.0]               # or a band, sampled as [sampling] says

    [sampling]                          # only with bands: seeded, over every band at once
    method = "latin_hypercube"          # or "sobol"
    samples = 8
    seed = 1

    [[objectives]]                      # optional: two collected quantities give a Pareto front
    quantity = "transmission_angle_min_deg"
    goal = "max"                        # or "min"

    [executor]                          # optional
    workers = 2                         # local processes (default: one per core)
    case_timeout_s = 600.0              # a case running longer is recorded as a timeout
    attempts = 3                        # runs of a case whose worker dies before it is recorded as crashed
    scheduler = "tcp://HOST:8786"       # a Dask cluster instead of local processes

The cases are the product of the lists and ranges, times the band samples when there are bands.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any

from transplanter.errors import ProblemError
from transplanter.study.field_paths import check_path
from transplanter.toml_fields import LONGEST_TITLE, FieldReader, is_finite_number, read_toml

#: How band samples are drawn (scipy.stats.qmc).
SAMPLING_METHODS = ("latin_hypercube", "sobol")
#: The most cases a study may have: beyond it the product of the lists is more likely a mistake than a plan.
MOST_CASES = 100_000


@dataclass(frozen=True)
class Varied:
    """One varied field: its TOML path and either its values (a list or a range) or a band to sample."""

    field: str
    values: tuple[Any, ...] = ()
    band: tuple[float, float] | None = None


@dataclass(frozen=True)
class Objective:
    """A collected quantity the Pareto front minimises (``goal`` "min") or maximises ("max")."""

    quantity: str
    goal: str


@dataclass(frozen=True)
class ExecutorSettings:
    """The [executor] table: local workers (None: one per core), the case timeout, a Dask scheduler."""

    workers: int | None = None
    case_timeout_s: float | None = None
    attempts: int = 3
    scheduler: str | None = None


@dataclass(frozen=True)
class StudySpec:
    """A validated study: the command, the problem file's content, what varies and what is collected."""

    source: str
    title: str
    command: str
    problem_file: str
    problem: dict
    varied: tuple[Varied, ...]
    collect: tuple[str, ...]
    sampling: str = "latin_hypercube"
    samples: int = 0
    seed: int = 0
    objectives: tuple[Objective, ...] = ()
    executor: ExecutorSettings = field(default_factory=ExecutorSettings)

    @property
    def fields(self) -> tuple[str, ...]:
        """The varied fields' paths, in the file's order."""
        return tuple(v.field for v in self.varied)


def load_study(path: str | Path) -> StudySpec:
    """Read and validate a study file (schema above); ProblemError naming the file, field and value."""
    return parse_study(read_toml(path), str(path), Path(path).parent)


def _range_values(read: FieldReader, row: dict, where: str) -> tuple[float, ...]:
    """low, low + step, ... up to high; whole numbers when low, high and step are."""
    low, high = read.numbers(row, "range", where, 2)[[0, -1]]
    step = read.number(row, "step", where)
    if len(row["range"]) != 2 or not low <= high or not step > 0:
        read.fail(f"{where}.range", row["range"], "[low, high] with low <= high and a positive step")
    count = math.floor((high - low) / step * (1 + 1e-12)) + 1
    if count > MOST_CASES:
        read.fail(f"{where}.step", step, f"a step giving at most {MOST_CASES} values over the range")
    whole = all(isinstance(v, int) and not isinstance(v, bool) for v in [*row["range"], row["step"]])
    return tuple(int(low) + k * int(step) if whole else float(low + k * step) for k in range(count))


def _varied(read: FieldReader, row: dict, where: str, problem: dict) -> Varied:
    read.keys(row, {"field", "values", "range", "step", "band"}, where)
    check_path(problem, row.get("field"), read.source, f"{where}.field")
    given = [key for key in ("values", "range", "band") if key in row]
    if len(given) != 1:
        read.fail(where, {k: row[k] for k in given}, "one of values = [...], range = [low, high] with step, or "
                                                     "band = [low, high]")
    if "step" in row and given != ["range"]:
        read.fail(f"{where}.step", row["step"], "a step only with range = [low, high]")
    if given == ["values"]:
        values = row["values"]
        if not isinstance(values, list) or not values or not all(
                is_finite_number(v) or isinstance(v, (str, bool)) for v in values):
            read.fail(f"{where}.values", values, "a list of at least one number, text or flag")
        return Varied(row["field"], tuple(values))
    if given == ["range"]:
        return Varied(row["field"], _range_values(read, row, where))
    low, high = read.numbers(row, "band", where, 2)[[0, -1]]
    if len(row["band"]) != 2 or not low < high:
        read.fail(f"{where}.band", row["band"], "[low, high] with low < high")
    return Varied(row["field"], band=(float(low), float(high)))


def _objectives(read: FieldReader, data: dict, collect: tuple[str, ...]) -> tuple[Objective, ...]:
    rows = read.tables(data, "objectives", "an array of tables [[objectives]] with quantity and goal") \
        if "objectives" in data else []
    objectives = []
    for k, row in enumerate(rows):
        where = f"objectives[{k}]"
        read.keys(row, {"quantity", "goal"}, where)
        if row.get("quantity") not in collect:
            read.fail(f"{where}.quantity", row.get("quantity"),
                      f"one of the collected quantities ({', '.join(collect)})")
        if row.get("goal") not in ("min", "max"):
            read.fail(f"{where}.goal", row.get("goal"), '"min" or "max"')
        objectives.append(Objective(row["quantity"], row["goal"]))
    if len(objectives) not in (0, 2):
        read.fail("objectives", rows, "two objectives (a Pareto front is drawn over two), or none")
    return tuple(objectives)


def _executor(read: FieldReader, table: dict) -> ExecutorSettings:
    read.keys(table, {"workers", "case_timeout_s", "attempts", "scheduler"}, "executor")
    workers = read.integer(table, "workers", "executor", 1, 1024) if "workers" in table else None
    timeout = read.number(table, "case_timeout_s", "executor") if "case_timeout_s" in table else None
    if timeout is not None and not timeout > 0:
        read.fail("executor.case_timeout_s", timeout, "a positive number of seconds")
    attempts = read.integer(table, "attempts", "executor", 1, 100, default=3)
    scheduler = table.get("scheduler")
    if scheduler is not None and (not isinstance(scheduler, str) or "://" not in scheduler):
        read.fail("executor.scheduler", scheduler, "a Dask scheduler address such as tcp://HOST:8786")
    return ExecutorSettings(workers, timeout, attempts, scheduler)


def parse_study(data: dict, source: str = "<dict>", folder: str | Path = ".") -> StudySpec:
    """Validate a study given as a dict with the fields of the file; ``problem`` is read relative to ``folder``."""
    from transplanter.cli import COMMANDS

    read = FieldReader(source)
    read.keys(data, {"title", "description", "command", "problem", "collect", "vary", "sampling", "objectives",
                     "executor"}, "")
    title = read.text(data, "title", "", LONGEST_TITLE, default="Design study")
    commands = {command.name: command for command in COMMANDS}
    if data.get("command") not in commands:
        read.fail("command", data.get("command"), f"one of the design commands ({', '.join(commands)})")
    if not isinstance(data.get("problem"), str) or not data["problem"]:
        read.fail("problem", data.get("problem"), "the name of the command's problem file, relative to the study file")
    problem_file = str(Path(folder) / data["problem"])
    problem = read_toml(problem_file)
    collect = data.get("collect", [])
    if not isinstance(collect, list) or not all(isinstance(c, str) and c for c in collect) \
            or len(set(collect)) != len(collect):
        read.fail("collect", collect, "a list of distinct report.json paths (e.g. design.carrier_length_OA)")
    varied = tuple(_varied(read, row, f"vary[{k}]", problem)
                   for k, row in enumerate(read.tables(data, "vary", "an array of tables [[vary]], one per field")))
    if not varied:
        read.fail("vary", [], "at least one [[vary]] table")
    fields = [v.field for v in varied]
    for name in fields:
        if fields.count(name) > 1 or name in collect:
            read.fail("vary", name, "each field varied once, and named apart from the collected quantities")
    sampling = data.get("sampling", {})
    read.keys(sampling, {"method", "samples", "seed"}, "sampling")
    bands = any(v.band for v in varied)
    if bands != bool(sampling):
        read.fail("sampling", sampling, "a [sampling] table when a field has a band, and none otherwise")
    method = sampling.get("method", SAMPLING_METHODS[0])
    if method not in SAMPLING_METHODS:
        read.fail("sampling.method", method, " or ".join(f'"{m}"' for m in SAMPLING_METHODS))
    samples = read.integer(sampling, "samples", "sampling", 1, MOST_CASES) if bands else 0
    if method == "sobol" and samples & (samples - 1):
        read.fail("sampling.samples", samples, "a power of 2 with sobol (its points are balanced only then)")
    seed = read.integer(sampling, "seed", "sampling", 0, 2**32 - 1, default=0)
    spec = StudySpec(source, title, data["command"], problem_file, problem, varied, tuple(collect), method, samples,
                     seed, _objectives(read, data, tuple(collect)), _executor(read, data.get("executor", {})))
    grid = math.prod(len(v.values) for v in varied if not v.band)
    if grid * max(samples, 1) > MOST_CASES:
        read.fail("vary", fields, f"at most {MOST_CASES} cases (the lists give {grid}, times {max(samples, 1)} "
                                  "samples)")
    return spec


def replace_scheduler(spec: StudySpec, scheduler: str | None) -> StudySpec:
    """``spec`` run on the Dask scheduler at ``scheduler`` (``--scheduler``), or as it is when None."""
    if scheduler is None:
        return spec
    if "://" not in scheduler:
        raise ProblemError(f"--scheduler = {scheduler}: expected a Dask scheduler address such as tcp://HOST:8786")
    return replace(spec, executor=replace(spec.executor, scheduler=scheduler))

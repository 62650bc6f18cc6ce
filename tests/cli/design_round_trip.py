"""The check of every design command's round trip: the numbers a run's report.json gives for its design,
reproduced by ``--design design.toml`` (the file the run wrote)."""
import json
import math

#: Agreement asked of a number read back: relative to its size, absolute below 1.
AGREEMENT = 1e-9


def numbers_apart(first, second, where: str = "") -> list[str]:
    """Where two JSON values differ: a number by more than ``AGREEMENT`` (relative above 1), anything else at all."""
    if isinstance(first, dict) and isinstance(second, dict) and first.keys() == second.keys():
        return [line for key in first for line in numbers_apart(first[key], second[key], f"{where}.{key}")]
    if isinstance(first, list) and isinstance(second, list) and len(first) == len(second):
        return [line for k, (a, b) in enumerate(zip(first, second, strict=True))
                for line in numbers_apart(a, b, f"{where}[{k}]")]
    numbers = (int, float)
    if isinstance(first, numbers) and isinstance(second, numbers) and not isinstance(first, bool):
        close = abs(first - second) <= AGREEMENT * max(1.0, abs(first), abs(second))
        return [] if close and math.isfinite(first) else [f"{where}: {first!r} != {second!r}"]
    return [] if first == second else [f"{where}: {first!r} != {second!r}"]


def assert_round_trip(run_report: dict, design_report: dict, keys: tuple[str, ...]):
    """Each of ``keys`` of the run's report.json equals the ``--design`` run's to ``AGREEMENT``."""
    apart = [line for key in keys for line in numbers_apart(run_report[key], design_report[key], key)]
    assert not apart, "\n".join(apart)


def read_report(folder) -> dict:
    """report.json of an output folder."""
    return json.loads((folder / "report.json").read_text())

"""The onion transplanter: the published optimum of the onion-transplanter paper evaluated (``--design``), the
command, bad input."""
import json
from pathlib import Path

import pytest

from transplanter import parallelogram
from transplanter.cli import main

ROOT = Path(__file__).resolve().parents[2]
PROBLEM = ROOT / "examples/onion_transplanter.toml"
PUBLISHED = ROOT / "examples/onion_published.toml"


@pytest.fixture(scope="module")
def published():
    problem = parallelogram.load_problem(PROBLEM)
    return problem, parallelogram.evaluate_design(problem, parallelogram.load_design(PUBLISHED), tolerance=False)


def _row(report, curve, conventions):
    (row,) = [e for e in report.evaluations if e.label == curve and e.conventions == conventions]
    return row


def test_published_optimum_with_the_closed_curve(published):
    """Corrected curve (m12 = 0.75 from eq 2, closing a): the paper's spacing (300 mm), release near zero speed
    (under 1 % of the machine speed) and a depth within 3 mm of its 27 mm under the file's conventions; but
    Y = 2 l1 = 164 mm, not the printed 163."""
    problem, report = published
    row = _row(report, "closed", "file")
    assert row.center_distance == pytest.approx(report.gear.design.center_distance, rel=1e-12)
    assert row.driven_turn_deg == pytest.approx(360.0, rel=1e-12)
    assert row.spacing == pytest.approx(300.0, rel=1e-12)
    assert abs(row.vx_release) < 0.01 * problem.forward_speed
    assert abs(row.depth - 27.0) < 3.0
    assert row.vertical_range == pytest.approx(2 * 82.0, rel=1e-12)
    assert abs(row.vertical_range - 163.0) > 0.5


def test_published_optimum_with_the_printed_curve(published):
    """Eq (19) as printed (m12 = 0.375) at a = 110 mm: the driven gear turns 423 deg per driver turn (not
    closed), so plants are 255 mm apart, and at the file's phase the release is far from zero speed."""
    problem, report = published
    row = _row(report, "as printed", "file")
    assert row.driven_turn_deg > 400
    assert row.spacing == pytest.approx(300.0 * 360.0 / row.driven_turn_deg, rel=1e-12)
    assert abs(row.vx_release) > 0.5 * problem.forward_speed
    assert row.depth < 1.0


def test_eq17_read_literally_cannot_release_at_zero_speed(published):
    """Crank at phi2 - alpha from +x, counted from phi1 = 0: the lowest point comes where the crank is fast and
    E moves faster than the machine (|Vx| > v), for both curves."""
    problem, report = published
    for curve in ("as printed", "closed"):
        assert abs(_row(report, curve, "eq (17) literal").vx_release) > problem.forward_speed


def test_design_json_and_figures(tmp_path, capsys):
    """``--design --json --out``: the published evaluation, the gear, the trajectory summary and the tolerance
    section (the design's own, the fraction of built mechanisms outside the depth band); figures written.
    The published optimum's depth under the file's conventions (24.996 mm) is below the band [25, 30] mm, so
    the run is FAILED (exit 1) and says so in one line naming the depth."""
    out = tmp_path / "out"
    code = main(["parallelogram", str(PROBLEM), "--design", str(PUBLISHED), "--json", "--no-step", "--out", str(out)])
    err = capsys.readouterr().err.strip()
    assert code == 1
    report = json.loads((out / "FAILED-report.json").read_text())
    low, high = parallelogram.load_problem(PROBLEM).depth_band
    depth = report["trajectory"]["depth_mm"]
    assert not low <= depth <= high
    assert report["status"] == "FAILED" and report["failures"] == [f"depth {depth:.4f} mm outside the band [25, 30] mm"]
    assert len(err.splitlines()) == 1 and f"depth {depth:.4f} mm" in err
    assert {"published", "gear", "trajectory", "timings_s"} <= set(report)
    assert len(report["published"]["evaluations"]) == 4
    assert report["gear"]["teeth"] == [54, 54] and report["gear"]["convex"] == [True, True]
    assert report["published"]["paper"]["depth_mm"] == 27.0
    assert {"FAILED-trajectory.png", "FAILED-velocity.png", "FAILED-acceleration.png", "FAILED-tolerance_band.png",
            "FAILED-report.md"} <= {p.name for p in out.iterdir()}
    design = parallelogram.load_design(PUBLISHED).design
    nominal = {d["name"]: d["nominal"] for d in report["tolerance"]["dimensions"]}
    assert nominal["l1"] == pytest.approx(design["l1"], rel=1e-12) and nominal["l6"] == pytest.approx(design["l6"])
    # the design plants below the band's low end: more than half of the built ones do too
    assert 0.5 < report["tolerance"]["violation_fraction"]["depth band"] < 1
    assert "## Tolerances (the built mechanism)" in (out / "FAILED-report.md").read_text()
    skipped = tmp_path / "skipped"
    assert main(["parallelogram", str(PROBLEM), "--design", str(PUBLISHED), "--quiet", "--no-tolerance", "--no-step",
                 "--out", str(skipped)]) == 1
    assert "tolerance" not in json.loads((skipped / "FAILED-report.json").read_text())
    assert not (skipped / "FAILED-tolerance_band.png").exists()


@pytest.mark.parametrize("alpha_deg", [6.3, 0.0])
def test_a_design_passes_exactly_when_it_meets_the_band_and_gear_checks(alpha_deg, tmp_path):
    """The published design turned to another phase alpha: exit 0 when its own evaluation plants within the
    depth band with a convex, undercut-free gear pair, else exit 1 (at alpha = 0 it plants 9 mm deep)."""
    path = tmp_path / "design.toml"
    path.write_text(PUBLISHED.read_text().replace("alpha_deg = 6.0", f"alpha_deg = {alpha_deg}"))
    problem = parallelogram.load_problem(PROBLEM)
    report = parallelogram.evaluate_design(problem, parallelogram.load_design(path), tolerance=False)
    low, high = problem.depth_band
    gear = report.gear.to_json()
    meets = low <= report.closed.depth <= high and all(gear["convex"]) and not any(gear["undercut"] or ())
    assert report.passed == meets
    assert main(["parallelogram", str(PROBLEM), "--design", str(path), "--quiet", "--no-tolerance"]) == (0 if meets
                                                                                                      else 1)
    assert meets == (alpha_deg == 6.3)      # both outcomes are exercised


BAD = {
    "inverted bounds": ({"search": {"bounds": {"l1": [100.0, 60.0]}}}, "search.bounds.l1"),
    "empty bounds": ({"search": {"bounds": {"m11": [1.2, 1.2]}}}, "search.bounds.m11"),
    "zero speed": ({"machine": {"forward_speed_mm_s": 0.0}}, "machine.forward_speed_mm_s"),
    "gear cannot close": ({"search": {"bounds": {"b": [5.0, 45.0], "l": [40.0, 70.0]}}}, "search.bounds.b"),
    "translation-only bound": ({"search": {"bounds": {"l6": [100.0, 200.0]}}}, "search.bounds.l6"),
    "bad convention": ({"conventions": {"crank_sense": "cw"}}, "conventions.crank_sense"),
    "depth target outside the band": ({"objectives": {"depth_target_mm": 40.0}}, "objectives.depth_target_mm = 40.0"),
    "a search too long to finish": ({"search": {"population": 5000, "generations": 100000}},
                                    "search.generations = 100000: expected at most 200"),
    "a population past its cap": ({"search": {"population": 5001}},
                                  "search.population = 5001: expected a whole number from 8 to 5000"),
}


@pytest.mark.parametrize("name", sorted(BAD))
def test_bad_input_names_the_field(name, tmp_path, capsys):
    import tomllib

    changes, field = BAD[name]
    data = tomllib.loads(PROBLEM.read_text())
    for table, values in changes.items():
        if table == "search" and "bounds" in values:
            data["search"]["bounds"] = {**data["search"]["bounds"], **values["bounds"]}
        else:
            data[table] = {**data[table], **values}
    path = tmp_path / "bad.toml"
    path.write_text(_toml(data))
    code = main(["parallelogram", str(path), "--design", str(PUBLISHED), "--json"])
    err = capsys.readouterr().err.strip()
    assert code == 2
    assert len(err.splitlines()) == 1 and field in err and "expected" in err


def _toml(data: dict) -> str:
    """Just enough TOML for the problem files here."""
    def value(v):
        if isinstance(v, str):
            return json.dumps(v)
        if isinstance(v, list):
            return "[" + ", ".join(value(x) for x in v) + "]"
        return repr(float(v)) if isinstance(v, float) else str(v).lower() if isinstance(v, bool) else str(v)

    lines = [f"{k} = {value(v)}" for k, v in data.items() if not isinstance(v, dict)]
    for table, fields in data.items():
        if isinstance(fields, dict):
            lines.append(f"[{table}]")
            lines += [f"{k} = {value(v)}" for k, v in fields.items() if not isinstance(v, dict)]
            for sub, inner in ((k, v) for k, v in fields.items() if isinstance(v, dict)):
                lines.append(f"[{table}.{sub}]")
                lines += [f"{k} = {value(v)}" for k, v in inner.items()]
    return "\n".join(lines) + "\n"

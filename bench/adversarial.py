"""Adversarial runs of every command, from the command line and the Python API, in fresh processes: bad files,
sizes past every cap, gear expressions, the API given the wrong types, signals at every rename of the publishing
step and at instants around the end of a run, Ctrl-C twice, and two runs at once on one ``--out``.

Each case prints one row: the case, its exit code, the number of stderr lines, whether stderr holds a traceback,
whether it hung (killed after ``--timeout`` seconds), and what ``--out`` holds after it: "old" (the earlier output,
complete), "new" (the run's output, complete), "missing", "partial" (files and report.json disagree, or a work
folder left beside it) or "-" (no --out). A case is clean when its exit code is one the case allows, stderr is at
most one line (none for exit 0), there is no traceback or hang, and --out is old or new, complete.

    python bench/adversarial.py                       # every class, 50 instants per command around the end
    python bench/adversarial.py --classes files sizes --instants 10 --commands burmester gear

The unit suite checks one case of most classes (tests/cli/test_bounded_reading.py, test_size_caps.py,
test_bad_and_extreme_inputs.py, test_interrupt_at_publishing.py, test_interrupt_while_starting.py,
tests/api/test_arguments_at_the_door.py); this script runs every class against every command, which takes many
minutes.
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import textwrap
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"

#: Each command's quickest example and the flags that keep it quick.
COMMANDS = {
    "burmester": ("burmester_3poses.toml", []),
    "gear": ("gear_ellipse.toml", []),
    "cam": ("cam_flat_faced.toml", []),
    "pickup": ("pickup_forward.toml", ["--no-animation"]),
    "reverse": ("rice_hoe_reverse.toml", ["--no-tolerance"]),
    "parallelogram": ("onion_transplanter.toml", ["--no-tolerance", "--no-animation"]),
    "fivebar": ("vegetable_planting.toml", ["--no-tolerance", "--no-animation"]),
}


@dataclass
class Case:
    """One adversarial run: ``argv`` after ``python -m transplanter`` (or ``code`` for ``python -c``), the exit
    codes it may end with, and what to do while it runs (``during``: called with the process)."""

    name: str
    kind: str
    argv: list[str] = field(default_factory=list)
    code: str = ""
    allowed: tuple[int, ...] = (2,)
    out: Path | None = None
    during: Callable[[subprocess.Popen], None] | None = None
    also: list[str] | None = None          # a second command line started at the same moment (same --out)


@dataclass
class Row:
    name: str
    kind: str
    exit: int | None
    lines: int
    traceback: bool
    hung: bool
    out: str
    allowed: tuple[int, ...]
    stderr: str

    @property
    def clean(self) -> bool:
        return (self.exit in self.allowed and not self.traceback and not self.hung
                and self.out in ("old", "new", "-") and self.lines <= (0 if self.exit == 0 else 1))


def out_state(out: Path | None) -> str:
    """What ``out`` holds (module docstring)."""
    if out is None:
        return "-"
    if any(p.name.startswith(f".{out.name}.") for p in out.parent.iterdir()):
        return "partial"
    if not out.exists():
        return "missing"
    try:
        report = json.loads((out / "report.json").read_text())
    except (OSError, ValueError):
        return "partial"
    listed = {name for names in report.get("files", {}).values() for name in names}
    if set(os.listdir(out)) != listed:
        return "partial"
    return "old" if "marker.csv" in listed else "new"


def earlier_output(command: str, out: Path, cache: dict[str, Path]) -> Path:
    """A complete earlier output of ``command`` at ``out`` (made once, copied), with a marker file it lists."""
    if command not in cache:
        made = Path(tempfile.mkdtemp()) / "made"
        example, flags = COMMANDS[command]
        subprocess.run([sys.executable, "-m", "transplanter", command, str(EXAMPLES / example), *flags,
                        "--out", str(made), "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        report = json.loads((made / "report.json").read_text())
        (made / "marker.csv").write_text("earlier\n")
        report["files"]["table"] = [*report["files"].get("table", []), "marker.csv"]
        (made / "report.json").write_text(json.dumps(report))
        cache[command] = made
    shutil.copytree(cache[command], out)
    return out


def run(case: Case, timeout: float) -> Row:
    command = [sys.executable, "-c", case.code] if case.code else [sys.executable, "-m", "transplanter", *case.argv]
    process = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    second = (subprocess.Popen([sys.executable, "-m", "transplanter", *case.also], stdout=subprocess.DEVNULL,
                               stderr=subprocess.PIPE, text=True) if case.also else None)
    if case.during:
        case.during(process)
    hung = False
    try:
        _, err = process.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        _, err = process.communicate()
        hung = True
    if second:
        _, more = second.communicate(timeout=timeout)
        err += more
        if second.returncode not in case.allowed:
            err += f"second run exited {second.returncode}\n"
    return Row(case.name, case.kind, None if hung else process.returncode, err.count("\n"), "Traceback" in err,
               hung, out_state(case.out), case.allowed, err)


def _write(folder: Path, name: str, text: str) -> str:
    path = folder / name
    path.write_text(text)
    return str(path)


def file_cases(folder: Path, commands) -> list[Case]:
    """A FIFO, /dev/zero, a folder, 5000 nested arrays, 3000 nested inline tables, a name with a line break, a
    missing file, a 300-character --out name: for every command, exit 2 with one line."""
    fifo = folder / "fifo.toml"
    os.mkfifo(fifo)
    arrays = _write(folder, "arrays.toml", "a = " + "[" * 5000 + "]" * 5000 + "\n")
    tables = _write(folder, "tables.toml", "a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n")
    cases = []
    for command in commands:
        example = EXAMPLES / COMMANDS[command][0]
        broken = folder / f"line\nbreak {command}.toml"
        shutil.copy(example, broken)
        broken.write_text(broken.read_text() + "\nnot toml at all\n")
        for name, path in (("fifo", str(fifo)), ("/dev/zero", "/dev/zero"), ("folder", str(folder)),
                           ("5000 nested arrays", arrays), ("3000 nested tables", tables),
                           ("line break in the name", str(broken)), ("missing", str(folder / "none.toml"))):
            cases.append(Case(f"{command}: {name}", "files", [command, path]))
        cases.append(Case(f"{command}: 300-char --out", "files",
                          [command, str(example), "--out", str(folder / ("o" * 300)), "--quiet"]))
    return cases


def size_cases(folder: Path, commands) -> list[Case]:
    """Every user-sized list or count one past its cap, and far past it (a file past 16 MB): exit 2."""
    made = {
        "gear": [("ratio samples 20,001", _ratio_file(20001)), ("ratio samples 2,500,000", _ratio_file(2_500_000))],
        "reverse": [("path points 20,001", _path_file(20001)), ("path points 1,000,000", _path_file(1_000_000))],
        "burmester": [("poses 1001", _poses_file(1001)), ("poses 20,000", _poses_file(20000))],
        "cam": [("samples 1,000,000", (EXAMPLES / "cam_flat_faced.toml").read_text().replace(
            "[cam]", "[cam]\nsamples = 1000000", 1))],
        "parallelogram": [("population 10,001", (EXAMPLES / "onion_transplanter.toml").read_text().replace(
            "population = 100", "population = 10001"))],
        "fivebar": [("return points 1000", (EXAMPLES / "vegetable_planting.toml").read_text() + "".join(
            f"\n[[return_points]]\nx = {-40 - k * 1e-3}\ny = -229.0\n" for k in range(1000)))],
        "pickup": [("spline radius 20,001", (EXAMPLES / "pickup_forward.toml").read_text().split("[stage1.driver]")[0]
                    + f'[stage1.driver]\nfamily = "spline"\nphi_deg = {[k * 360 / 20001 for k in range(20001)]}\n'
                    f"radius = {[30.0] * 20001}\n"
                    + "[stage2" + (EXAMPLES / "pickup_forward.toml").read_text().split("[stage2", 1)[1])],
    }
    cases = []
    for command in commands:
        for name, text in made.get(command, []):
            path = _write(folder, f"{command} {name}.toml".replace(",", ""), text)
            cases.append(Case(f"{command}: {name}", "sizes", [command, path, "--quiet"]))
    return cases


def _ratio_file(count: int) -> str:
    phi = ", ".join(f"{360 * k / count:.9g}" for k in range(count))
    ratio = ", ".join("1.0" for _ in range(count))
    return (f'[driver]\nfamily = "ratio"\ncorrect = true\nphi_deg = [{phi}]\nratio = [{ratio}]\n'
            "[pair]\ncenter_distance = 90.0\n")


def _path_file(count: int) -> str:
    """An ellipse below the pivot sampled ``count`` times."""
    import math
    turns = [2 * math.pi * k / count for k in range(count)]
    points = ", ".join(f"[{40 * math.cos(t):.9g}, {-160 + 90 * math.sin(t):.9g}]" for t in turns)
    return f'[trajectory]\nkind = "samples"\npoints = [{points}]\n[arm]\ndirection = "clockwise"\n'


def _poses_file(count: int) -> str:
    import math
    rows = "".join(f"[[poses]]\nx = {100 * math.cos(k / count * 6):.9g}\ny = {80 * math.sin(k / count * 6):.9g}\n"
                   f"angle_deg = {30 * math.sin(k / count * 6):.9g}\n" for k in range(count))
    return rows


def expression_cases(folder: Path) -> list[Case]:
    """Ratio expressions that are complex, a negative base to a fractional power, beyond float range."""
    cases = []
    for expression in ("(-1)**0.5", "1 + (-8)**(1/3)", "1" + "0" * 400, "1e400 * phi", "2**2**2**2**2",
                       "1 + 0.3*cos(phi)**(1/2)", "exp(exp(exp(9)))", "1/(phi - phi)"):
        path = _write(folder, f"expr{len(cases)}.toml", f'[driver]\nfamily = "ratio"\nexpression = "{expression}"\n'
                                                        'correct = true\n[pair]\ncenter_distance = 50.0\n')
        cases.append(Case(f"gear: expression {expression[:30]}", "expressions", ["gear", path, "--quiet"]))
        cases.append(Case(f"API gears: expression {expression[:30]}", "expressions", code=_api(
            f"from transplanter import gears\ngears.synthesize(gears.parse_problem({{'driver': {{'family': 'ratio', "
            f"'expression': {expression!r}, 'correct': True}}, 'pair': {{'center_distance': 50.0}}}}))")))
    return cases


def _api(body: str) -> str:
    """Python that runs ``body``: a ProblemError or another TransplanterError ends it with one line and 2, anything
    else with its traceback."""
    return textwrap.dedent("""
        import sys
        from transplanter.errors import TransplanterError
        try:
        {body}
        except TransplanterError as error:
            print(f"{{type(error).__name__}}: {{error}}".replace("\\n", "\\\\n"), file=sys.stderr)
            sys.exit(2)
        """).format(body=textwrap.indent(body, "    "))


def api_cases() -> list[Case]:
    """Every public synthesize of the wrong problem class, None, a dict; options of the wrong type."""
    modules = ("burmester", "gears", "cam", "pickup", "reverse", "parallelogram", "fivebar")
    cases = []
    for module in modules:
        for name, value in (("None", "None"), ("a dict", "{}"), ("a number", "3.5"),
                            ("another problem", "burmester.load_problem('examples/burmester_3poses.toml')"
                             if module != "burmester" else "gears.load_problem('examples/gear_ellipse.toml')")):
            cases.append(Case(f"API {module}.synthesize({name})", "api", code=_api(
                f"import os\nos.chdir({str(ROOT)!r})\nfrom transplanter import burmester, gears, {module}\n"
                f"{module}.synthesize({value})")))
    for module, example, option in (("parallelogram", "onion_transplanter.toml", "pick='1'"),
                                    ("fivebar", "vegetable_planting.toml", "progress='yes'"),
                                    ("fivebar", "vegetable_planting.toml", "pick=0"),
                                    ("fivebar", "vegetable_planting.toml", "tolerance='no'"),
                                    ("parallelogram", "onion_transplanter.toml", "polish_nlp='no'"),
                                    ("reverse", "rice_hoe_reverse.toml", "tolerance='no'")):
        cases.append(Case(f"API {module}.synthesize(problem, {option})", "api", code=_api(
            f"from transplanter import {module}\n"
            f"{module}.synthesize({module}.load_problem({str(EXAMPLES / example)!r}), {option})")))
    return cases


def _signal_at(delay: float, number: int, again: float | None = None) -> Callable[[subprocess.Popen], None]:
    def during(process: subprocess.Popen):
        time.sleep(delay)
        if process.poll() is None:
            process.send_signal(number)
        if again is not None:
            time.sleep(again)
            if process.poll() is None:
                process.send_signal(number)
    return during


def duration(command: str) -> float:
    """Seconds one run of the command's example takes from start to exit, --out written."""
    with tempfile.TemporaryDirectory() as folder:
        example, flags = COMMANDS[command]
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "transplanter", command, str(EXAMPLES / example), *flags,
                        "--out", str(Path(folder) / "out"), "--quiet"], stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        return time.perf_counter() - start


def signal_cases(folder: Path, commands, instants: int, cache: dict[str, Path]) -> list[Case]:
    """SIGINT or SIGTERM at ``instants`` moments from 80 % to 110 % of a run's measured length (over an earlier
    output), Ctrl-C twice 0.3 s apart, and a signal at each rename of the publishing step (both ways of putting the
    folder in place): exit 0 or 130, --out old or new, complete."""
    cases = []
    for command in commands:
        example, flags = COMMANDS[command]
        length = duration(command)
        for k in range(instants):
            moment = length * (0.8 + 0.3 * k / max(instants - 1, 1))
            number = (signal.SIGINT, signal.SIGTERM)[k % 2]
            out = earlier_output(command, folder / f"{command}-signal-{k}", cache)
            cases.append(Case(f"{command}: {signal.Signals(number).name} at {moment:.2f} s of {length:.2f}", "signals",
                              [command, str(EXAMPLES / example), *flags, "--out", str(out), "--quiet"],
                              allowed=(0, 130), out=out, during=_signal_at(moment, number)))
        out = earlier_output(command, folder / f"{command}-twice", cache)
        cases.append(Case(f"{command}: Ctrl-C twice 0.3 s apart at {length / 2:.2f} s", "signals",
                          [command, str(EXAMPLES / example), *flags, "--out", str(out), "--quiet"], allowed=(130,),
                          out=out, during=_signal_at(length / 2, signal.SIGINT, 0.3)))
        for exchange in (True, False):
            for at in range(3):
                out = earlier_output(command, folder / f"{command}-rename-{exchange}-{at}", cache)
                cases.append(Case(f"{command}: SIGINT at rename {at} ({'exchange' if exchange else 'two renames'})",
                                  "renames", code=_renames_interrupted(command, out, at, exchange), allowed=(0, 130),
                                  out=out))
    return cases


def _renames_interrupted(command: str, out: Path, at: int, exchange: bool) -> str:
    """The program with SIGINT raised just before rename ``at`` of the publishing step (as the unit test does)."""
    example, flags = COMMANDS[command]
    argv = ["transplanter", command, str(EXAMPLES / example), *flags, "--out", str(out), "--quiet"]
    return textwrap.dedent(f"""
        import signal, sys
        from pathlib import Path
        from transplanter import folder_swap
        calls = []
        replace, exchange = Path.replace, folder_swap.exchange
        def interrupted():
            if len(calls) == {at}:
                signal.raise_signal(signal.SIGINT)
            calls.append(1)
        def replacing(self, target):
            if self.name.startswith(".") or self.parent.name.endswith(".partial"):
                interrupted()
            return replace(self, target)
        def exchanging(first, second):
            interrupted()
            return exchange(first, second) if {exchange} else False
        Path.replace = replacing
        folder_swap.exchange = exchanging
        sys.argv = {argv!r}
        from transplanter.entry_point import console
        console()
        """)


def concurrent_cases(folder: Path, commands, cache: dict[str, Path]) -> list[Case]:
    """Two runs started at once on one --out over an earlier output: both exit 0, --out new and complete."""
    cases = []
    for command in commands:
        example, flags = COMMANDS[command]
        out = earlier_output(command, folder / f"{command}-together", cache)
        argv = [command, str(EXAMPLES / example), *flags, "--out", str(out), "--quiet"]
        cases.append(Case(f"{command}: two runs on one --out", "concurrent", argv, allowed=(0,), out=out, also=argv))
    return cases


CLASSES = ("files", "sizes", "expressions", "api", "signals", "concurrent")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--classes", nargs="+", choices=CLASSES, default=list(CLASSES))
    parser.add_argument("--commands", nargs="+", choices=list(COMMANDS), default=list(COMMANDS))
    parser.add_argument("--instants", type=int, default=50, help="signal instants per command around the end")
    parser.add_argument("--timeout", type=float, default=600.0, help="seconds before a run counts as hung")
    args = parser.parse_args()
    cache: dict[str, Path] = {}
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        builders = {"files": lambda: file_cases(folder, args.commands),
                    "sizes": lambda: size_cases(folder, args.commands),
                    "expressions": lambda: expression_cases(folder) if "gear" in args.commands else [],
                    "api": api_cases,
                    "signals": lambda: signal_cases(folder, args.commands, args.instants, cache),
                    "concurrent": lambda: concurrent_cases(folder, args.commands, cache)}
        print(f"{'case':<62} {'exit':>5} {'lines':>5} {'traceback':>9} {'hung':>5} {'--out':>8}  clean")
        rows = []
        for kind in args.classes:
            for case in builders[kind]():
                start = time.perf_counter()
                row = run(case, args.timeout)
                rows.append(row)
                print(f"{row.name[:62]:<62} {str(row.exit):>5} {row.lines:>5} {str(row.traceback):>9} "
                      f"{str(row.hung):>5} {row.out:>8}  {'yes' if row.clean else 'NO'}"
                      f"  ({time.perf_counter() - start:.1f} s)", flush=True)
                if not row.clean:
                    print(textwrap.indent(row.stderr[-2000:], "    | "), flush=True)
        for kind in args.classes:
            some = [row for row in rows if row.kind == kind]
            print(f"{kind}: {sum(row.clean for row in some)} clean of {len(some)}")
        print(f"all: {sum(row.clean for row in rows)} clean of {len(rows)}")


if __name__ == "__main__":
    main()

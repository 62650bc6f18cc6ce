"""``transplanter <command>``: parses arguments, calls the library's API, saves the report and the
figures; no logic of its own.

Conventions of every design command: ``--out DIR`` is written whole or not at all
(``output_folder.staged``) and its report.json lists every file under "files" by kind; progress
of the longer steps goes to stderr when it is a terminal (as git does; a pipe or a log gets only
errors), unless ``--quiet`` or ``--json``; exit 0 when the result
passes its checks, 1 when it fails one (every file name then starts with FAILED- and the reports
say why), 2 for bad input or no result (one line; inputs, ``--out`` and ``--plot`` are checked
before the work), 130 for Ctrl-C; report.json is always valid JSON (``output_folder.report_json``).
"""
from __future__ import annotations

import argparse
import contextlib
import io
import signal
import sys
import threading
import warnings
from pathlib import Path

from transplanter import __version__, progress
from transplanter.errors import TransplanterError
from transplanter.output_folder import FAILED_PREFIX, check_file, files_by_kind, report_json, staged, staged_file

#: What ``--plot`` may be named (the formats matplotlib writes without extra packages).
PLOT_SUFFIXES = {".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".webp"}


def _failures(*checked) -> tuple[str, ...]:
    """Why the result fails: the ``failures`` of every object whose ``passed`` is False."""
    return tuple(reason for item in checked if getattr(item, "passed", True) is False
                 for reason in (getattr(item, "failures", None) or [f"{type(item).__name__} failed its checks"]))


def _publish(args, report: dict, file_text: str, screen_text: str, failures: tuple[str, ...] = ()) -> int:
    """Write report.md and report.json beside the files already in the output folder (listed in the
    report under "files"), print the JSON (--json) or the screen text, the same way for every command.
    A result that failed a check is marked FAILED (report status, file names) and exits 1."""
    if failures:
        report = {"status": "FAILED", "failures": list(failures), **report}
        file_text = "# FAILED: " + "; ".join(failures) + "\n\n" + file_text
        screen_text = "FAILED: " + "; ".join(failures) + "\n" + screen_text
    folder, prefix = args.folder, FAILED_PREFIX if failures else ""
    report["files"] = {}
    if folder:
        (folder / "report.md").write_text(file_text)
        names = sorted(path.name for path in folder.iterdir())
        report["files"] = files_by_kind(prefix + name for name in [*names, "report.json"])
        (folder / f"{prefix}report.json").write_text(report_json(report) + "\n")
        for name in names if prefix else ():
            (folder / name).rename(folder / (prefix + name))
    if args.json:
        sys.stdout.write(report_json(report, indent=None) + "\n")
    else:
        sys.stdout.write(screen_text)
        if folder:
            sys.stdout.write(f"wrote {args.out}/: " + ", ".join(n for names in report["files"].values() for n in names)
                             + "\n")
    if failures:
        _say(f"transplanter: failed: {report.get('source', args.file)}: " + "; ".join(failures), args.warned)
        return 1
    return 0


def _say(line: str, warned: list):
    """The one stderr line of a run that ends with exit 1, 2 or 130, the run's warnings folded into it."""
    print(line + "".join(f"; warning: {w.message}" for w in warned), file=sys.stderr)


def _save_figures(figures: dict, out: Path, dpi: int = 120) -> list[str]:
    """Save each Figure as ``<stem>.png`` in ``out``; the names written."""
    out.mkdir(parents=True, exist_ok=True)
    for stem, figure in figures.items():
        figure.savefig(out / f"{stem}.png", dpi=dpi)
    return [f"{stem}.png" for stem in figures]


def _burmester(args) -> int:
    from transplanter import burmester
    from transplanter.burmester.report import to_markdown, to_text

    plot = check_file(args.plot, "--plot", PLOT_SUFFIXES, args.out) if args.plot else None
    problem = burmester.load_problem(args.file)
    with progress.step("synthesis"):
        result = burmester.synthesize(problem)
    if plot or args.folder:
        with progress.step("figures"):
            figures = burmester.draw_figures(result)
            if plot:
                with staged_file(plot) as partial:
                    figures["burmester"].savefig(partial, dpi=130)
            if args.folder:
                _save_figures(figures, args.folder, dpi=130)
    return _publish(args, result.to_json(), to_markdown(result, "burmester.png"), to_text(result), _failures(result))


def _gear(args) -> int:
    from transplanter import gears
    from transplanter.gears.report import to_markdown

    problem = gears.load_problem(args.file)
    with progress.step("synthesis"):
        result = gears.synthesize(problem)
    report = result.to_json()
    drawings, figures = [], []
    if args.folder:
        with progress.step("drawings"):
            drawings = [p.name for p in gears.write_drawings(result, args.folder)]
        with progress.step("figures"):
            figures = _save_figures(gears.draw_figures(result), args.folder)
    return _publish(args, report, to_markdown(report, figures, drawings),
                    to_markdown(report, [], []).replace("# ", "", 1), _failures(result))


def _fivebar(args) -> int:
    from transplanter import fivebar
    from transplanter.fivebar.report import evaluation_markdown, to_markdown

    problem = fivebar.load_problem(args.file)
    if args.design:
        evaluation = fivebar.evaluate_design(problem, fivebar.load_design(args.design))
        if args.folder and evaluation.support:
            from transplanter.cam import write_drawings as write_cam_drawings

            with progress.step("drawings"):
                write_cam_drawings(evaluation.support.cam, args.folder)
        report = evaluation.to_json()
        return _publish(args, report, evaluation_markdown(report, problem.labels),
                        evaluation_markdown(report, problem.labels), _failures(evaluation.candidate, evaluation.support))
    with progress.step("synthesis"):
        result = fivebar.synthesize(problem, pick=args.pick, progress=_report)
    report = result.to_json()
    figures = []
    if args.folder:
        from transplanter.fivebar.animation import write_animation
        from transplanter.fivebar.drawings import write_drawings
        from transplanter.fivebar.gears_on_carrier import teeth_on_carrier

        with progress.step("figures"):
            figures = _save_figures(fivebar.draw_figures(result), args.folder)
        with progress.step("drawings"):
            write_drawings(result, args.folder)
        if not args.no_animation:
            with progress.step("animation"):
                teeth = teeth_on_carrier(result.toothed, result.design.mech.carrier_length)
                write_animation(result, args.folder, teeth)
    text = to_markdown(report, problem.labels, figures)
    return _publish(args, report, text, text, _failures(result))


def _reverse(args) -> int:
    from transplanter import reverse
    from transplanter.reverse.report import to_markdown

    problem = reverse.load_problem(args.file)
    with progress.step("synthesis"):
        result = reverse.synthesize(problem)
    report = result.to_json()
    figures = []
    if args.folder:
        with progress.step("figures"):
            figures = _save_figures(reverse.draw_figures(result), args.folder)
    code = _publish(args, report, to_markdown(report, figures), to_markdown(report, []), _failures(result))
    return code if result.monotonic else 2          # no train: no result, though the report gives the hints


def _cam(args) -> int:
    from transplanter import cam
    from transplanter.cam.report import to_markdown

    problem = cam.load_problem(args.file)
    with progress.step("synthesis"):
        result = cam.synthesize(problem)
    drawings, figures = [], []
    if args.folder:
        with progress.step("drawings"):
            drawings = [path.name for path in cam.write_drawings(result, args.folder)]
        with progress.step("figures"):
            figures = _save_figures(cam.draw_figures(result), args.folder)
    report = result.to_json()
    return _publish(args, report, to_markdown(report, figures, drawings),
                    to_markdown(report, [], []).replace("# ", "", 1), _failures(result))


def _parallelogram(args) -> int:
    from transplanter import parallelogram
    from transplanter.parallelogram.report import evaluation_markdown, to_markdown

    problem = parallelogram.load_problem(args.file)
    if args.design:
        given = parallelogram.load_design(args.design)
        with progress.step("evaluation"):
            result = parallelogram.evaluate_design(problem, given)
        report = result.to_json()
        figures = []
        if args.folder:
            with progress.step("figures"):
                figures = _save_figures(parallelogram.draw_design_figures(problem, given.design), args.folder)
        return _publish(args, report, evaluation_markdown(report, figures), evaluation_markdown(report),
                        _failures(result))
    with progress.step("search"):
        result = parallelogram.synthesize(problem, pick=args.pick, progress=_report)
    report = result.to_json()
    figures = []
    if args.folder:
        from transplanter.parallelogram.tables import write_tables

        with progress.step("figures"):
            figures = _save_figures(parallelogram.draw_figures(result), args.folder)
        with progress.step("tables"):
            write_tables(result, args.folder)
        if result.gear.teeth is not None:
            from transplanter.gears import write_drawings

            with progress.step("drawings"):
                write_drawings(result.gear, args.folder)
        if not args.no_animation:
            from transplanter.parallelogram.animation import write_animation

            with progress.step("animation"):
                write_animation(result, args.folder)
    return _publish(args, report, to_markdown(report, figures), to_markdown(report), _failures(result))


def _pickup(args) -> int:
    from transplanter import pickup
    from transplanter.pickup.report import to_markdown

    problem = pickup.load_problem(args.file)
    with progress.step("kinematics"):
        result = pickup.synthesize(problem)
    report = result.to_json()
    files = []
    if args.folder:
        with progress.step("figures"):
            files = _save_figures(pickup.draw_figures(result), args.folder)
        if not args.no_animation:
            with progress.step("animation"):
                files.append(pickup.write_animation(result, args.folder).name)
    return _publish(args, report, to_markdown(report, files), to_markdown(report, []).replace("# ", "", 1))


def _derive(args) -> int:
    from transplanter.derive import run_build

    return run_build(["--check"] if args.check else [])


def _command(commands, name: str, run, summary: str, file_help: str, extras: str, animation: str | None = None):
    """A subcommand with the arguments every design command takes: FILE, --json, --out DIR, --quiet; and
    --no-animation when it writes the animation file ``animation``."""
    command = commands.add_parser(name, help=summary)
    command.add_argument("file", help=file_help)
    command.add_argument("--json", action="store_true", help="print the report as one JSON object (no progress)")
    command.add_argument("--out", metavar="DIR", help=f"write report.md, report.json and {extras} here (the "
                         "folder is replaced only when the run succeeds)")
    command.add_argument("--quiet", action="store_true", help="no progress on stderr")
    if animation:
        command.add_argument("--no-animation", action="store_true", help=f"with --out: skip {animation} (one cycle)")
    command.set_defaults(run=run)
    return command


class _OneLineParser(argparse.ArgumentParser):
    """argparse's parser, but a bad command line gives one line on stderr (and exit 2), as every other bad input."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _parser() -> argparse.ArgumentParser:
    parser = _OneLineParser(prog="transplanter", description="Synthesis of seedling transplanting mechanisms.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    burmester = _command(commands, "burmester", _burmester, "RR dyads that guide a body through 3 or more poses",
                         "problem file (TOML, mm and degrees)", "the figure")
    burmester.add_argument("--plot", metavar="PNG", help="write the figure to this file")
    _command(commands, "gear", _gear, "a pair of non-circular gears: pitch curves, closure, teeth, drawings",
             "gear problem file (TOML, mm and degrees)", "CSV/SVG/DXF drawings and figures")
    fivebar = _command(commands, "fivebar", _fivebar, "five-bar seedling pushing mechanism with its planetary gear "
                       "train (Wang et al. 2025): region, precise design, gears, verification",
                       "five-bar problem file (TOML, mm and degrees)",
                       "the figures, linkage.dxf, CSV tables and animation.gif", "animation.gif")
    given_or_picked = fivebar.add_mutually_exclusive_group()     # --pick ranks designed alternatives; --design has one
    given_or_picked.add_argument("--design", metavar="DESIGN.toml",
                                 help="evaluate this given design instead of designing one")
    given_or_picked.add_argument("--pick", metavar="N", type=int, help="build alternative N of the ranked alternatives "
                         "(default 1, the best; report.md lists them)")
    _command(commands, "reverse", _reverse, "planetary non-circular gear train that makes the arm tip follow a closed "
             "path (the rice-transplanter, reverse-gear-design and cusp-pitch-curve papers): inverse kinematics, "
             "monotonicity, gears, round trip",
             "reverse-design problem file (TOML, mm and degrees)", "the figures")
    _command(commands, "cam", _cam, "a disc cam with a roller follower (translating or oscillating): motion laws, "
             "profile, pressure angle, curvature, undercut, the smallest base circle",
             "cam problem file (TOML, mm and degrees)", "cam_profile.csv, cam.dxf, cam.svg and the figures")
    parallelogram = _command(commands, "parallelogram", _parallelogram, "onion transplanter: parallelogram planting "
                             "mechanism driven by denatured Pascal limacon gears, NSGA-II and NLP polish",
                             "parallelogram problem file (TOML, mm and degrees)",
                             "figures, pareto.csv, trajectory.csv, gear drawings and animation.gif", "animation.gif")
    given_or_picked = parallelogram.add_mutually_exclusive_group()
    given_or_picked.add_argument("--design", metavar="DESIGN.toml", help="evaluate this given design (e.g. "
                               "examples/onion_published.toml) instead of searching")
    given_or_picked.add_argument("--pick", metavar="N", type=int, help="build the N-th Pareto design, ranked by "
                               "distance to the ideal point (default 1, the knee)")
    _command(commands, "pickup", _pickup, "the seedling pick-up mechanism of the cusp-pitch-curve paper "
                      "(eq 15), forward: tip path, picking and pushing angles, tip speed, animation",
                      "pick-up problem file (TOML, mm and degrees)", "the figures and pickup.gif", "pickup.gif")
    derive = commands.add_parser("derive", help="regenerate src/transplanter/_generated from derivations/")
    derive.add_argument("--check", action="store_true", help="exit 1 if the generated code is out of step")
    derive.set_defaults(run=_derive)
    return parser


def main(argv: list[str] | None = None) -> int:
    """Run a command; its warnings (a pose in radians, a figure that cannot be laid out) are printed one line each
    after a run that exits 0, and folded into the one line of a run that does not."""
    args = _parser().parse_args(argv)
    with warnings.catch_warnings(record=True) as args.warned:
        code = _run(args)
    for warning in args.warned if code == 0 else ():
        print(f"transplanter: warning: {warning.message}", file=sys.stderr)
    return code


def _run(args) -> int:
    out = getattr(args, "out", None)
    _STOP.clear()
    handlers = {number: signal.signal(number, _interrupt) for number in (signal.SIGINT, signal.SIGTERM)} \
        if threading.current_thread() is threading.main_thread() else {}
    try:
        quiet = getattr(args, "json", False) or getattr(args, "quiet", False)
        with _stderr_until_interrupted(), progress.showing(sys.stderr, enabled=sys.stderr.isatty() and not quiet):
            with staged(out) as args.folder:
                code = args.run(args)
                if _STOP.is_set():          # a solver that caught the interrupt and went on
                    raise KeyboardInterrupt
                return code
    except TransplanterError as error:
        _say(f"transplanter: error: {error}", args.warned)
        return 2
    except OSError as error:            # a disk that fills or a file that goes away under the run
        _say(f"transplanter: error: {error.filename or out or 'a file'}: {error.strerror or error}"
             + (f"; {out} is left as it was" if out else ""), args.warned)
        return 2
    except KeyboardInterrupt:
        _say("transplanter: interrupted" + (f"; {out} is left as it was" if out else ""), args.warned)
        return 130
    finally:
        for number, handler in handlers.items():
            signal.signal(number, handler)


#: Set by Ctrl-C or SIGTERM during a run. IPOPT's callbacks turn the KeyboardInterrupt raised inside a solve into a
#: failed solve, and the refinements would go on: the run checks this after each candidate and before publishing.
_STOP = threading.Event()


def _interrupt(signum, frame):
    """Ctrl-C or SIGTERM (a timeout, a job scheduler) ends the run: the output folder's partial copy is removed."""
    _STOP.set()
    raise KeyboardInterrupt


class _UntilInterrupted(io.TextIOBase):
    """stderr that passes everything until the run is interrupted, and nothing after: CasADi reports the
    KeyboardInterrupt it catches inside IPOPT as a warning of its own, through Python's stderr."""

    def __init__(self, stream):
        self.stream = stream

    def write(self, text: str) -> int:
        if not _STOP.is_set():
            self.stream.write(text)
        return len(text)

    def flush(self):
        self.stream.flush()

    def isatty(self) -> bool:
        return self.stream.isatty()


@contextlib.contextmanager
def _stderr_until_interrupted():
    """``sys.stderr`` is a ``_UntilInterrupted`` inside the block, the real one again for the run's last line."""
    real, sys.stderr = sys.stderr, _UntilInterrupted(sys.stderr)
    try:
        yield
    finally:
        sys.stderr = real


def _report(step: str, done: int, total: int) -> None:
    """``progress.report``, where a run stops after an interrupt that a solver swallowed."""
    if _STOP.is_set():
        raise KeyboardInterrupt
    progress.report(step, done, total)


if __name__ == "__main__":
    sys.exit(main())

"""``transplanter <command>``: parses arguments, calls the library's API, saves the report and the
figures; no logic of its own.

One runner (``_run_command``) serves every design command of the registry ``COMMANDS``: it reads the
problem with the command's subpackage, runs the job, and reports the ``CommandResult`` it returns.
Conventions of every design command: ``--out DIR`` is written whole or not at all
(``output_folder.staged``) and its report.json lists every file under "files" by kind; progress
of the longer steps goes to stderr when it is a terminal (as git does; a pipe or a log gets only
errors), unless ``--quiet`` or ``--json``; exit 0 when the result
passes its checks, 1 when it fails one (every file name then starts with FAILED- and the reports
say why), 2 for bad input or no result (one line; inputs, ``--out`` and ``--plot`` are checked
before the work; a result without its mechanism still gets its FAILED report), 130 for Ctrl-C;
report.json is always valid JSON (``output_folder.report_json``).
"""
from __future__ import annotations

import argparse
import atexit
import contextlib
import io
import os
import signal
import sys
import threading
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from types import ModuleType
from typing import TYPE_CHECKING, Any, NoReturn

from transplanter import __version__, burmester, cam, fivebar, gears, parallelogram, pickup, progress, reverse
from transplanter.command_result import CommandResult
from transplanter.errors import TransplanterError
from transplanter.folder_swap import INTERRUPTS, interrupts_held
from transplanter.output_folder import (
    FAILED_PREFIX,
    check_file,
    files_by_kind,
    report_json,
    staged,
    staged_file,
)
from transplanter.shared_calls import share_calls

if TYPE_CHECKING:
    from matplotlib.figure import Figure

#: What ``--plot`` may be named (the formats matplotlib writes without extra packages).
PLOT_SUFFIXES = {".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff", ".webp"}


def _publish(args, result: CommandResult, files: list[str]) -> int:
    """Write report.md and report.json beside the files already in the output folder (listed in the
    report under "files"), print the JSON (--json) or the screen text, the same way for every command.
    A result that failed a check is marked FAILED (report status, file names) and exits 1, or 2 when
    no mechanism was made (``CommandResult.produced``)."""
    report, file_text, screen_text = result.to_json(), result.to_markdown(files), result.to_text()
    failures = [] if result.passed else list(result.failures)
    if failures:
        report = {"status": "FAILED", "failures": failures, **report}
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
    if result.passed:
        return 0
    _say(f"transplanter: failed: {result.source}: " + "; ".join(failures), args.warned)
    return 1 if result.produced else 2


def _say(line: str, warned: list):
    """The one stderr line of a run that ends with exit 1, 2 or 130, the run's warnings folded into it; a line
    break inside (a file name holding one) is written as its escape, so the line stays one."""
    text = line + "".join(f"; warning: {w.message}" for w in warned)
    print(text.translate(_ESCAPES), file=sys.stderr)


#: Characters that would end or hide part of a line, and how ``_say`` writes them.
_ESCAPES = {code: repr(chr(code))[1:-1] for code in [*range(32), 127, 0x85, 0x2028, 0x2029] if code != 9}


#: zlib level of the PNG figures: the five-bar's ten save in 2.26-2.58 s at level 1 against 2.47-2.74 s at
#: matplotlib's 6, for 1,049 KB against 948 (``bench/bench_outputs.py``; the figures are the main job's last step).
PNG_COMPRESSION = 1


def _save_figure(figure: Figure, path: Path, dpi: int) -> None:
    figure.savefig(path, dpi=dpi, pil_kwargs={"compress_level": PNG_COMPRESSION})


def _run_command(command: Command, args) -> int:
    """One design command: check ``--plot``, load the problem, run the job, save the figures and the files,
    publish the report; the exit code follows the result (``_publish``)."""
    plot = check_file(args.plot, "--plot", PLOT_SUFFIXES, args.out) if command.plot and args.plot else None
    problem = command.package.load_problem(args.file)
    result = command.run(command, problem, args)
    files: list[str] = []
    with staged_file(plot) if plot else contextlib.nullcontext() as partial:
        drawers = result.figure_drawers()

        def saved(stem: str) -> str:
            """Figure ``stem`` drawn and saved (as ``--plot`` too when it is that one): its file name."""
            figure = drawers[stem]()
            if partial and stem == command.plot:
                figure.savefig(partial, dpi=command.dpi)
            _save_figure(figure, args.folder / f"{stem}.png", command.dpi)
            return f"{stem}.png"

        def written() -> list[str]:
            return [path.name for path in result.write_files(
                args.folder, animation=not getattr(args, "no_animation", False),
                solids=not getattr(args, "no_step", False))]

        if args.folder:     # the figures shared between a side process and this one, once its files are written
            args.folder.mkdir(parents=True, exist_ok=True)
            with progress.step("figures"):
                figure_files, other_files = share_calls(saved, [(stem,) for stem in drawers], written)
            files = figure_files + other_files
        elif partial and command.plot:
            with progress.step("figures"):
                drawers[command.plot]().savefig(partial, dpi=command.dpi)
    return _publish(args, result, files)


def _synthesize(command: Command, problem, args) -> CommandResult:
    """The job of a command without options: its subpackage's ``synthesize(problem)``."""
    with progress.step(command.step):
        return command.package.synthesize(problem)


def _fivebar(command: Command, problem, args) -> CommandResult:
    """A given design evaluated (``--design``), or a design made (``--pick`` builds another alternative)."""
    if args.design:
        return fivebar.evaluate_design(problem, fivebar.load_design(args.design))
    with progress.step("synthesis"):
        return fivebar.synthesize(problem, pick=args.pick, progress=_report, tolerance=not args.no_tolerance)


def _parallelogram(command: Command, problem, args) -> CommandResult:
    """A given design evaluated (``--design``), or the Pareto designs searched and one built (``--pick``)."""
    if args.design:
        given = parallelogram.load_design(args.design)
        with progress.step("evaluation"):
            return parallelogram.evaluate_design(problem, given, tolerance=not args.no_tolerance)
    with progress.step("search"):
        return parallelogram.synthesize(problem, pick=args.pick, progress=_report, tolerance=not args.no_tolerance)


def _reverse(command: Command, problem, args) -> CommandResult:
    """A given design's train (``--design``) or the problem's, with the tolerance analysis unless
    ``--no-tolerance``."""
    tolerance = not args.no_tolerance
    with progress.step(command.step):
        if args.design:
            return reverse.evaluate_design(problem, reverse.load_design(args.design), tolerance=tolerance)
        return reverse.synthesize(problem, tolerance=tolerance)


def _study(args) -> int:
    from transplanter.study.command import run_study

    return run_study(args, shown=sys.stderr.isatty() and not args.quiet)


def _given_or_made(command: Command, problem, args) -> CommandResult:
    """The job of a command whose ``--design`` sets what the problem file leaves to the design (the cam's base
    circle): its subpackage's ``evaluate_design`` of that design, or
    ``synthesize(problem)``."""
    with progress.step(command.step):
        if args.design:
            return command.package.evaluate_design(problem, command.package.load_design(args.design))
        return command.package.synthesize(problem)


def _derive(args) -> int:
    from transplanter.derive import run_build

    return run_build(["--check"] if args.check else [])


def _examples(args) -> int:
    from transplanter.bundled_examples import copy_examples

    written = copy_examples(args.dir)
    print(f"copied {len(written)} example files to {args.dir}")
    return 0


@dataclass(frozen=True)
class Flag:
    """An option of one command beyond those every design command takes: its names and argparse keywords;
    the ``exclusive`` flags of a command exclude each other."""

    names: tuple[str, ...]
    options: dict[str, Any]
    exclusive: bool = False


@dataclass(frozen=True)
class Command:
    """A design command: ``transplanter <name> FILE`` reads FILE with ``package.load_problem`` and reports
    the ``CommandResult`` that ``run(command, problem, args)`` returns.

    Attributes
    ----------
    name, summary, file_help : str
        The command, its line in ``--help`` and the help of FILE.
    writes : str
        What ``--out`` holds besides report.md and report.json (for ``--help``).
    package : module
        The subpackage whose public API runs the command.
    step : str
        The progress step of ``_synthesize``.
    run : callable
        The job: ``_synthesize`` unless the command has options of its own.
    flags : tuple of Flag
        The command's own options.
    animation : str or None
        The animation file ``--no-animation`` skips, for a command that writes one.
    plot : str or None
        The figure ``--plot FILE`` writes, for a command that offers it.
    dpi : int
        Resolution of the saved figures.
    """

    name: str
    summary: str
    file_help: str
    writes: str
    package: ModuleType
    step: str = "synthesis"
    run: Callable[[Command, Any, argparse.Namespace], CommandResult] = _synthesize
    flags: tuple[Flag, ...] = ()
    animation: str | None = None
    plot: str | None = None
    dpi: int = 120


#: The design commands that analyse their built mechanism's tolerances take this flag.
NO_TOLERANCE = Flag(("--no-tolerance",), {"action": "store_true", "help": "skip the tolerance analysis of the built "
                                          "mechanism (report section and figures)"})
#: The design commands that write STEP solids of their parts take this flag.
NO_STEP = Flag(("--no-step",), {"action": "store_true", "help": "with --out: skip the parts' STEP solids (they need "
                                "the optional extra transplanter[cad] and take seconds a part)"})

#: The design commands, in the order ``--help`` lists them.
COMMANDS = (
    Command("burmester", "RR dyads that guide a body through 3 or more poses", "problem file (TOML, mm and degrees)",
            "the figure", burmester, plot="burmester", dpi=130,
            flags=(Flag(("--plot",), {"metavar": "PNG", "help": "write the figure to this file"}),)),
    Command("gear", "a pair of non-circular gears: pitch curves, closure, teeth, drawings",
            "gear problem file (TOML, mm and degrees)", "CSV/SVG/DXF drawings and figures", gears, flags=(NO_STEP,)),
    Command("fivebar", "five-bar seedling pushing mechanism with its planetary gear train (Wang et al. 2025): region, "
            "precise design, gears, verification", "five-bar problem file (TOML, mm and degrees)",
            "the figures, part and assembly drawings (DXF, PDF, parts.csv), CSV tables and animation.gif", fivebar,
            run=_fivebar, animation="animation.gif",
            flags=(Flag(("--design",), {"metavar": "DESIGN.toml",
                                        "help": "evaluate this given design instead of designing one"}, exclusive=True),
                   Flag(("--pick",), {"metavar": "N", "type": int, "help": "build alternative N of the ranked "
                                      "alternatives (default 1, the best; report.md lists them)"}, exclusive=True),
                   NO_TOLERANCE, NO_STEP)),
    Command("reverse", "planetary non-circular gear train that makes the arm tip follow a closed path (the "
            "rice-transplanter, reverse-gear-design and cusp-pitch-curve papers): inverse kinematics, monotonicity, "
            "gears, round trip", "reverse-design problem file (TOML, mm and degrees)", "the figures and design.toml",
            reverse, run=_reverse,
            flags=(Flag(("--design",), {"metavar": "DESIGN.toml", "help": "make the train with this design's arm and "
                                        "train (a run's design.toml) instead of the file's"}),
                   NO_TOLERANCE, NO_STEP)),
    Command("cam", "a disc cam with a roller follower (translating or oscillating): motion laws, profile, pressure "
            "angle, curvature, undercut, the smallest base circle", "cam problem file (TOML, mm and degrees)",
            "cam_profile.csv, cam.dxf, cam.svg, design.toml and the figures", cam, run=_given_or_made,
            flags=(Flag(("--design",), {"metavar": "DESIGN.toml", "help": "make the cam on this design's base circle "
                                        "(a run's design.toml) instead of the file's or the smallest"}), NO_STEP)),
    Command("parallelogram", "onion transplanter: parallelogram planting mechanism driven by denatured Pascal limacon "
            "gears, NSGA-II and NLP polish", "parallelogram problem file (TOML, mm and degrees)",
            "figures, pareto.csv, trajectory.csv, gear drawings and animation.gif", parallelogram, run=_parallelogram,
            animation="animation.gif",
            flags=(Flag(("--design",), {"metavar": "DESIGN.toml", "help": "evaluate this given design (e.g. "
                                        "examples/onion_published.toml) instead of searching"}, exclusive=True),
                   Flag(("--pick",), {"metavar": "N", "type": int, "help": "build the N-th Pareto design, ranked by "
                                      "distance to the ideal point (default 1, the knee)"}, exclusive=True),
                   NO_TOLERANCE, NO_STEP)),
    Command("pickup", "the seedling pick-up mechanism of the cusp-pitch-curve paper (eq 15), forward: tip path, "
            "picking and pushing angles, tip speed, animation", "pick-up problem file (TOML, mm and degrees)",
            "the figures and pickup.gif", pickup, step="kinematics", animation="pickup.gif"),
)


def _add_command(commands, command: Command):
    """A subcommand with the arguments every design command takes: FILE, --json, --out DIR, --quiet; and
    --no-animation when it writes an animation, then its own flags."""
    parser = commands.add_parser(command.name, help=command.summary)
    parser.add_argument("file", help=command.file_help)
    parser.add_argument("--json", action="store_true", help="print the report as one JSON object (no progress)")
    parser.add_argument("--out", metavar="DIR", help=f"write report.md, report.json and {command.writes} here (the "
                        "folder is replaced only when the run succeeds)")
    parser.add_argument("--quiet", action="store_true", help="no progress on stderr")
    if command.animation:
        parser.add_argument("--no-animation", action="store_true",
                            help=f"with --out: skip {command.animation} (one cycle)")
    exclusive = parser.add_mutually_exclusive_group() if any(flag.exclusive for flag in command.flags) else None
    for flag in command.flags:
        (exclusive if flag.exclusive and exclusive else parser).add_argument(*flag.names, **flag.options)
    parser.set_defaults(run=lambda args: _run_command(command, args))


class _OneLineParser(argparse.ArgumentParser):
    """argparse's parser, but a bad command line gives one line on stderr (and exit 2), as every other bad input."""

    def error(self, message: str):
        self.exit(2, f"{self.prog}: error: {message} (see {self.prog} --help)\n")


def _parser() -> argparse.ArgumentParser:
    parser = _OneLineParser(prog="transplanter", description="Synthesis of seedling transplanting mechanisms.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    for command in COMMANDS:
        _add_command(commands, command)
    study = commands.add_parser("study", help="many cases of one design command from a study file, on local "
                                "processes or a Dask cluster; each case kept as it finishes")
    study.add_argument("file", help="study file (TOML; docs/study.md)")
    study.add_argument("--out", metavar="DIR", dest="study_out", required=True,
                       help="write cases.csv, cases/<case_id>/report.json, report.md, report.json and the figures here")
    study.add_argument("--resume", action="store_true", help="run only the cases DIR lacks")
    study.add_argument("--scheduler", metavar="tcp://HOST:8786",
                       help="run the cases on this Dask cluster (pip install 'transplanter[cluster]')")
    study.add_argument("--quiet", action="store_true", help="no progress bar on stderr")
    study.set_defaults(run=_study)
    derive = commands.add_parser("derive", help="regenerate src/transplanter/_generated from derivations/")
    derive.add_argument("--check", action="store_true", help="exit 1 if the generated code is out of step")
    derive.set_defaults(run=_derive)
    examples = commands.add_parser("examples", help="copy the bundled example problem files into DIR")
    examples.add_argument("dir", metavar="DIR", help="the folder to copy them into (made if missing; a file of the "
                          "same name there is never overwritten)")
    examples.set_defaults(run=_examples)
    return parser


def command_defaults(name: str, file: str) -> argparse.Namespace:
    """The arguments ``transplanter <name> FILE`` runs with when no option is given (each case of a study runs
    with them, so a command's new option reaches the study with its default)."""
    return _parser().parse_args([name, file])


def main(argv: list[str] | None = None) -> int:
    """Run a command; its warnings (a pose in radians, a figure that cannot be laid out) are printed one line each
    after a run that exits 0, and folded into the one line of a run that does not. Ctrl-C and SIGTERM end it
    with 130 (``_interrupt``); the handlers in place before are given back."""
    args = _parser().parse_args(argv)
    _RUN.stopped = _RUN.working = False
    handlers = {number: signal.signal(number, _interrupt) for number in INTERRUPTS} \
        if threading.current_thread() is threading.main_thread() else {}
    try:
        with warnings.catch_warnings(record=True) as args.warned:
            code = _run(args)
    finally:
        for number, handler in handlers.items():
            signal.signal(number, handler)
    if _RUN.stopped and code != 130:    # noted after the run's own last look: its output is complete
        _say("transplanter: interrupted after the run" + (f"; {args.out} holds its new output, complete"
                                                          if getattr(args, "out", None) else ""), args.warned)
        return 130
    for warning in args.warned if code == 0 else ():
        print(f"transplanter: warning: {warning.message}", file=sys.stderr)
    return code


def _run(args) -> int:
    out = getattr(args, "out", None)
    try:
        quiet = getattr(args, "json", False) or getattr(args, "quiet", False)
        with (_stderr_until_interrupted(), progress.showing(sys.stderr, enabled=sys.stderr.isatty() and not quiet),
              staged(out) as args.folder):
            try:
                _RUN.working = True
                code = args.run(args)
            finally:
                _RUN.working = False    # from here an interrupt is noted, not raised: the run ends as it began
            if _RUN.stopped:            # a solver that caught the interrupt and went on, or an interrupt just now
                raise KeyboardInterrupt
    except TransplanterError as error:
        if _RUN.stopped:                # an error the interrupt caused (a side process it ended)
            return _interrupted(out, args.warned)
        _say(f"transplanter: error: {error}", args.warned)
        return 2
    except OSError as error:            # a disk that fills or a file that goes away under the run
        _say(f"transplanter: error: {error.filename or out or 'a file'}: {error.strerror or error}"
             + (f"; {out} is left as it was" if out else ""), args.warned)
        return 2
    except (KeyboardInterrupt, Exception) as error:
        # an interrupt raised inside a library's C call can come out as another error (CasADi's: SystemError)
        if not isinstance(error, KeyboardInterrupt) and not _RUN.stopped:
            raise
        return _interrupted(out, args.warned)
    return code


def _interrupted(out, warned: list) -> int:
    """Exit 130 with its one line: the run was stopped (Ctrl-C, SIGTERM) and ``out`` left as it was."""
    _say("transplanter: interrupted" + (f"; {out} is left as it was" if out else ""), warned)
    return 130


class _Run:
    """The state of a run that its signal handler reads and sets (plain attributes: reading one calls no Python
    code that an interrupt could cut into).

    Attributes
    ----------
    working : bool
        The run is at its work: an interrupt raises KeyboardInterrupt there. Past it (the new output being put
        in place) an interrupt is only noted.
    stopped : bool
        Ctrl-C or SIGTERM came. IPOPT's callbacks turn the KeyboardInterrupt raised inside a solve into a failed
        solve, and the refinements would go on: the run looks at this after each candidate and before publishing.
    """

    working = False
    stopped = False


_RUN = _Run()


def _interrupt(signum, frame):
    """Ctrl-C or SIGTERM (a timeout, a job scheduler) ends the run at its work: the output folder's partial copy is
    removed and the earlier output kept. Past the work it is noted and the run ends with 130 once the new output
    is in place. A second one does nothing: raised inside the clean-up, it would cut it short."""
    first = not _RUN.stopped
    _RUN.stopped = True
    if first and _RUN.working:
        raise KeyboardInterrupt


def console() -> NoReturn:
    """The ``transplanter`` program: ``main()``, then exit with its code. An interrupt after the run (its
    output complete) ends it with 130 and says so in one line; one after that is ignored: the run's ending is
    already decided. The program ends with ``os._exit`` once its output is flushed and the exit functions have run
    (multiprocessing's among them, which release a study's worker queues: skipped, the resource tracker reports
    leaked semaphores on stderr): the interpreter's shutdown (destroying CasADi objects a solve left when it was
    interrupted) killed it with SIGINT after its last line, in 2 of 14 runs of the pick-up interrupted near its
    end."""
    late = threading.Event()
    for number in INTERRUPTS:
        signal.signal(number, lambda signum, frame: late.set())
    code = main()
    with interrupts_held():
        for number in INTERRUPTS:
            signal.signal(number, signal.SIG_IGN)
        if late.is_set() and code != 130:
            print("transplanter: interrupted after the run; its output is complete", file=sys.stderr)
            code = 130
    atexit._run_exitfuncs()     # the public atexit has no other way to run them before os._exit
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError):
            stream.flush()
    os._exit(code)


class _UntilInterrupted(io.TextIOBase):
    """stderr that passes everything until the run is interrupted, and nothing after: CasADi reports the
    KeyboardInterrupt it catches inside IPOPT as a warning of its own, through Python's stderr."""

    def __init__(self, stream):
        self.stream = stream

    def write(self, text: str) -> int:
        if not _RUN.stopped:
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
    if _RUN.stopped:
        raise KeyboardInterrupt
    progress.report(step, done, total)


if __name__ == "__main__":
    console()

"""``transplanter <command>``: parses arguments, calls the library's API, saves the report and the
figures; no logic of its own."""
from __future__ import annotations

import argparse
import json
import sys
import warnings
from pathlib import Path

from transplanter import __version__
from transplanter.errors import TransplanterError


def _publish(args, report: dict, file_text: str, screen_text: str, written: list[str]):
    """Write report.json and report.md (next to ``written``, already in --out) and print the
    JSON (--json) or the screen text, the same way for every command."""
    if args.out:
        out = Path(args.out)
        out.mkdir(parents=True, exist_ok=True)
        (out / "report.json").write_text(json.dumps(report, indent=2) + "\n")
        (out / "report.md").write_text(file_text)
    if args.json:
        json.dump(report, sys.stdout)
        sys.stdout.write("\n")
    else:
        sys.stdout.write(screen_text)
        if args.out:
            sys.stdout.write(f"wrote {args.out}/" + ", ".join(["report.md", "report.json", *written]) + "\n")


def _save_figures(figures: dict, out: Path, dpi: int = 120) -> list[str]:
    """Save each Figure as ``<stem>.png`` in ``out``; the names written."""
    out.mkdir(parents=True, exist_ok=True)
    for stem, figure in figures.items():
        figure.savefig(out / f"{stem}.png", dpi=dpi)
    return [f"{stem}.png" for stem in figures]


def _burmester(args) -> int:
    from transplanter import burmester
    from transplanter.burmester.report import to_markdown, to_text

    result = burmester.synthesize(burmester.load_problem(args.file))
    written = []
    if args.plot or args.out:
        figures = burmester.draw_figures(result)
        if args.plot:
            figures["burmester"].savefig(args.plot, dpi=130)
        if args.out:
            written = _save_figures(figures, Path(args.out), dpi=130)
    _publish(args, result.to_json(), to_markdown(result, "burmester.png"), to_text(result), written)
    return 0


def _gear(args) -> int:
    from transplanter import gears
    from transplanter.gears.report import to_markdown

    result = gears.synthesize(gears.load_problem(args.file))
    report = result.to_json()
    drawings, figures = [], []
    if args.out:
        drawings = [p.name for p in gears.write_drawings(result, Path(args.out))]
        figures = _save_figures(gears.draw_figures(result), Path(args.out))
    _publish(args, report, to_markdown(report, figures, drawings),
             to_markdown(report, [], []).replace("# ", "", 1), drawings + figures)
    return 0


def _fivebar(args) -> int:
    from transplanter import fivebar
    from transplanter.fivebar.report import evaluation_markdown, to_markdown

    problem = fivebar.load_problem(args.file)
    if args.design:
        report = fivebar.evaluate_design(problem, fivebar.load_design(args.design)).to_json()
        text, figures = evaluation_markdown(report, problem.labels), []
    else:
        result = fivebar.synthesize(problem, pick=args.pick)
        report = result.to_json()
        figures = _save_figures(fivebar.draw_figures(result), Path(args.out)) if args.out else []
        text = to_markdown(report, problem.labels, figures)
    _publish(args, report, text, text, figures)
    return 0


def _reverse(args) -> int:
    from transplanter import reverse
    from transplanter.reverse.report import to_markdown

    result = reverse.synthesize(reverse.load_problem(args.file))
    report = result.to_json()
    figures = _save_figures(reverse.draw_figures(result), Path(args.out)) if args.out else []
    _publish(args, report, to_markdown(report, figures), to_markdown(report, []), figures)
    if not result.monotonic:
        print(f"transplanter: error: {result.problem.source}: the path fails the monotonicity criterion: "
              + "; ".join(v.message for v in result.violations), file=sys.stderr)
        return 2
    return 0


def _derive(args) -> int:
    from transplanter.derive import run_build

    return run_build(["--check"] if args.check else [])


def _command(commands, name: str, run, summary: str, file_help: str, extras: str):
    """A subcommand with the arguments every design command takes: FILE, --json, --out DIR."""
    command = commands.add_parser(name, help=summary)
    command.add_argument("file", help=file_help)
    command.add_argument("--json", action="store_true", help="print the report as one JSON object")
    command.add_argument("--out", metavar="DIR", help=f"write report.md, report.json and {extras} here")
    command.set_defaults(run=run)
    return command


def _parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="transplanter", description="Synthesis of seedling transplanting mechanisms.")
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    commands = parser.add_subparsers(dest="command", required=True)
    burmester = _command(commands, "burmester", _burmester, "RR dyads that guide a body through 3 or more poses",
                         "problem file (TOML, mm and degrees)", "the figure")
    burmester.add_argument("--plot", metavar="PNG", help="write the figure to this file")
    _command(commands, "gear", _gear, "a pair of non-circular gears: pitch curves, closure, teeth, drawings",
             "gear problem file (TOML, mm and degrees)", "CSV/SVG/DXF drawings and figures")
    fivebar = _command(commands, "fivebar", _fivebar, "five-bar seedling pushing mechanism with its planetary gear "
                       "train (Wang et al. 2025): region, precise design, gears, verification",
                       "five-bar problem file (TOML, mm and degrees)", "the figures")
    fivebar.add_argument("--design", metavar="DESIGN.toml", help="evaluate this given design instead of designing one")
    fivebar.add_argument("--pick", metavar="N", type=int, help="build alternative N of the ranked alternatives "
                         "(default 1, the best; report.md lists them)")
    _command(commands, "reverse", _reverse, "planetary non-circular gear train that makes the arm tip follow a closed "
             "path (the rice-transplanter, reverse-gear-design and cusp-pitch-curve papers): inverse kinematics, "
             "monotonicity, gears, round trip",
             "reverse-design problem file (TOML, mm and degrees)", "the figures")
    derive = commands.add_parser("derive", help="regenerate src/transplanter/_generated from derivations/")
    derive.add_argument("--check", action="store_true", help="exit 1 if the generated code is out of step")
    derive.set_defaults(run=_derive)
    return parser


def _one_line_warning(message, category, filename, lineno, file=None, line=None):
    return f"transplanter: warning: {message}\n"


def main(argv: list[str] | None = None) -> int:
    args = _parser().parse_args(argv)
    warnings.formatwarning = _one_line_warning
    try:
        return args.run(args)
    except TransplanterError as error:
        print(f"transplanter: error: {error}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())

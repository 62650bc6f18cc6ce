"""Every registered command's result is a ``CommandResult``: each command's quick example run through the
registry (the five-bar design itself is checked on the session's example in test_fivebar_drawings.py)."""
import dataclasses
from pathlib import Path

import pytest

from tests.cli.command_result_checks import check_protocol
from transplanter import parallelogram
from transplanter.cli import COMMANDS, Command, command_defaults
from transplanter.command_result import CommandResult
from transplanter.tolerance import ToleranceSettings

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
#: A quick run of each command through the registry: its problem file and its own flags.
QUICK = {"burmester": ("burmester_4poses.toml", {}), "gear": ("gear_ellipse.toml", {}),
         "reverse": ("rice_hoe_reverse.toml", {}), "cam": ("cam_translating_design.toml", {}),
         "pickup": ("pickup_forward.toml", {}),
         "fivebar --design": ("vegetable_planting.toml", {"design": EXAMPLES / "vegetable_planting_table4.toml"}),
         "parallelogram --design": ("onion_transplanter.toml", {"design": EXAMPLES / "onion_published.toml"})}


def _registered(name: str) -> Command:
    return next(command for command in COMMANDS if command.name == name)


def _run(name: str, problem, **flags) -> CommandResult:
    command = _registered(name)
    arguments = command_defaults(name, problem.source)       # as the command line runs it with no option given
    vars(arguments).update(flags)
    return command.run(command, problem, arguments)


@pytest.mark.parametrize("case", sorted(QUICK))
def test_a_registered_command_returns_a_command_result(case, tmp_path, request):
    name, design = case.split(" ")[0], QUICK[case][1]
    if name == "reverse":       # the rice hoe's train is the session's rice_full_result, synthesised as this runs it
        request.getfixturevalue("rice_result_from_synthesize")
    problem = _registered(name).package.load_problem(EXAMPLES / QUICK[case][0])
    check_protocol(_run(name, problem, **design), tmp_path)


def test_the_onion_transplanter_design_is_a_command_result(tmp_path):
    small = dataclasses.replace(parallelogram.load_problem(EXAMPLES / "onion_transplanter.toml"), population=12,
                                generations=4, depth_band=(10.0, 40.0), tolerances=ToleranceSettings(samples=200))
    check_protocol(_run("parallelogram", small), tmp_path)


def test_every_command_is_checked():
    """A command registered without a case here (or the five-bar's in test_fivebar_drawings.py) fails this."""
    assert {case.split(" ")[0] for case in QUICK} | {"fivebar", "parallelogram"} == {c.name for c in COMMANDS}

"""Every public synthesis checks what it is given before any work: a problem of the wrong class, a dict, a path
or None, and options of the wrong type give one ProblemError naming the argument, on one line, never an array's
repr and never an AttributeError or TypeError from inside."""
from __future__ import annotations

from pathlib import Path

import pytest

from transplanter import burmester, cam, fivebar, gears, parallelogram, pickup, reverse
from transplanter.errors import ProblemError

EXAMPLES = Path(__file__).resolve().parents[2] / "examples"
PACKAGES = {"burmester": burmester, "cam": cam, "fivebar": fivebar, "gears": gears, "parallelogram": parallelogram,
            "pickup": pickup, "reverse": reverse}


@pytest.fixture(scope="module")
def other_problem():
    """A problem of a class no other command takes (its repr holds numpy arrays over several lines)."""
    return burmester.load_problem(EXAMPLES / "burmester_3poses.toml")


@pytest.mark.parametrize("name", sorted(PACKAGES))
@pytest.mark.parametrize("given", ["none", "dict", "path", "other"])
def test_a_problem_of_the_wrong_kind_is_named(name, given, other_problem):
    problem = {"none": None, "dict": {"title": "x"}, "path": "problem.toml", "other": other_problem}[given]
    if name == "burmester" and given == "other":
        problem = fivebar.load_problem(EXAMPLES / "vegetable_planting.toml")
    with pytest.raises(ProblemError) as refused:
        PACKAGES[name].synthesize(problem)
    message = str(refused.value)
    assert message.startswith("problem = ") and "expected a " in message, message
    assert "\n" not in message and "array(" not in message, message


@pytest.mark.parametrize("name, problem_file", [("fivebar", "vegetable_planting.toml"),
                                                ("parallelogram", "onion_transplanter.toml")])
@pytest.mark.parametrize("option, value", [("pick", "1"), ("pick", 0), ("pick", True), ("pick", 1.5),
                                           ("progress", "yes"), ("progress", 3), ("tolerance", "no"),
                                           ("tolerance", None)])
def test_options_of_the_wrong_type_are_named(name, problem_file, option, value):
    """Before any work: a text for an on/off option (tolerance="no") would have switched it on."""
    package = PACKAGES[name]
    problem = package.load_problem(EXAMPLES / problem_file)
    with pytest.raises(ProblemError, match=rf"^(--)?{option} = .*: expected "):
        package.synthesize(problem, **{option: value})


@pytest.mark.parametrize("value", ["no", None, 0])
def test_reverse_tolerance_switch_is_named(value):
    """The reverse train's on/off option is checked at the door as the other commands' are."""
    problem = reverse.load_problem(EXAMPLES / "rice_hoe_reverse.toml")
    with pytest.raises(ProblemError, match=r"^(--)?tolerance = .*: expected "):
        reverse.synthesize(problem, tolerance=value)


@pytest.fixture(scope="module")
def gear_result():
    return gears.synthesize(gears.load_problem(EXAMPLES / "gear_ellipse.toml"))


@pytest.mark.parametrize("writer", ["method", "fivebar", "parallelogram"])
@pytest.mark.parametrize("switch", ["animation", "solids"])
@pytest.mark.parametrize("value", ["no", None, 0])
def test_write_files_switches_are_named(writer, switch, value, gear_result, tmp_path):
    """A text such as "no" for ``animation`` or ``solids`` would have switched it on; nothing is written."""
    write = {"method": gear_result.write_files, "fivebar": lambda *a, **k: fivebar.write_files(gear_result, *a, **k),
             "parallelogram": lambda *a, **k: parallelogram.write_files(gear_result, *a, **k)}[writer]
    with pytest.raises(ProblemError, match=rf"^{switch} = .*: expected True or False$"):
        write(tmp_path / "out", **{switch: value})
    assert not (tmp_path / "out").exists()

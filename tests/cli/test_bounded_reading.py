"""Problem files that could hang, exhaust memory or overflow the reader's stack are refused before they are
parsed, by every command, in one line naming the file (quoted where its name holds a line break); exit 2."""
from __future__ import annotations

import os
import threading

import pytest

from transplanter.cli import COMMANDS, main
from transplanter.toml_fields import DEEPEST_NESTING, LARGEST_FILE, read_toml
from transplanter.toml_nesting import nesting_depth

NAMES = [command.name for command in COMMANDS]


def _refused(capsys, argv: list[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    return err


@pytest.mark.parametrize("name", NAMES)
def test_deeply_nested_arrays_and_inline_tables_are_refused(tmp_path, capsys, name):
    arrays, tables = tmp_path / "arrays.toml", tmp_path / "tables.toml"
    arrays.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    tables.write_text("a = " + "{b = " * 3000 + "1" + "}" * 3000 + "\n")
    assert _refused(capsys, [name, str(arrays)]) == (f"transplanter: error: {arrays}: arrays or tables nested 5000 "
                                                      f"deep; expected at most {DEEPEST_NESTING}\n")
    assert "nested 3000 deep" in _refused(capsys, [name, str(tables)])


def test_a_fifo_nobody_writes_to_and_a_device_are_refused_at_once(tmp_path, capsys):
    fifo = tmp_path / "problem.toml"
    os.mkfifo(fifo)
    assert _refused(capsys, ["fivebar", str(fifo)]) == (f"transplanter: error: {fifo}: a FIFO (named pipe); "
                                                         "expected a TOML problem file\n")
    assert "a character device" in _refused(capsys, ["gear", "/dev/zero"])
    assert "a folder" in _refused(capsys, ["cam", str(tmp_path)])


def test_a_file_beyond_the_size_limit_is_refused_without_reading_it_whole(tmp_path, capsys):
    big = tmp_path / "big.toml"
    with big.open("wb") as handle:      # sparse: no disk is used
        handle.truncate(LARGEST_FILE + 1)
    assert "larger than 16 MB" in _refused(capsys, ["burmester", str(big)])
    exact = tmp_path / "exact.toml"
    exact.write_text("# " + "x" * (LARGEST_FILE - 3) + "\n")
    assert read_toml(exact) == {}       # at the limit it is read


def test_a_file_name_with_a_line_break_keeps_the_message_on_one_line(tmp_path, capsys):
    odd = tmp_path / "two\nlines.toml"
    err = _refused(capsys, ["reverse", str(odd)])
    assert err == f"transplanter: error: {str(odd)!r}: no such file\n"


def test_nesting_is_counted_outside_strings_and_comments():
    assert nesting_depth('a = "[[[[{{"\nb = \'\'\'\n[[[\n\'\'\' # [[[[\nc = [[1], {d = [2]}]\n[e.f]\n') == 3
    assert nesting_depth('a = """ \\""" [[[ """\n') == 0
    assert nesting_depth("[[table]]\nx = 1\n") == 2


def test_the_nesting_limit_is_below_what_the_reader_survives():
    """The limit must refuse what would overflow the parser's recursion, in a thread's smaller stack too."""
    text = "a = " + "[" * DEEPEST_NESTING + "]" * DEEPEST_NESTING + "\n"
    result: list = []
    worker = threading.Thread(target=lambda: result.append(__import__("tomllib").loads(text)))
    worker.start()
    worker.join()
    assert result and nesting_depth(text) == DEEPEST_NESTING

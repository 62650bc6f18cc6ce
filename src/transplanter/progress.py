"""Progress of the longer steps, shown on stderr only while a command asks for it.

The library reports through ``report(step, done, total)`` (the callback signature of the synthesis)
or ``with step("figures"):``; both are silent unless the caller has entered ``showing(stream)``,
as the command line does without ``--quiet`` or ``--json``. A few plain lines, no terminal tricks,
so logs and pipes stay readable.
"""
from __future__ import annotations

import contextlib
import contextvars
import io
import sys
import time
from typing import TextIO

_stream: contextvars.ContextVar[TextIO | None] = contextvars.ContextVar("progress_stream", default=None)


def _say(text: str):
    stream = _stream.get()
    if stream is not None:
        stream.write(f"transplanter: {text}\n")
        stream.flush()


def report(step: str, done: int, total: int) -> None:
    """``step`` has ``done`` of ``total`` parts done (e.g. refinements)."""
    _say(f"{step} {done}/{total}")


@contextlib.contextmanager
def step(name: str):
    """Announce ``name`` and say how long it took."""
    start = time.perf_counter()
    _say(f"{name} ...")
    yield
    _say(f"{name} done ({time.perf_counter() - start:.1f} s)")


@contextlib.contextmanager
def showing(stream: TextIO | None = None, enabled: bool = True):
    """Show progress on ``stream`` (stderr by default) inside the block, or keep it silent (``enabled`` False)."""
    token = _stream.set((stream or sys.stderr) if enabled else None)
    try:
        yield
    finally:
        _stream.reset(token)


@contextlib.contextmanager
def held():
    """Inside it, the lines that would be shown are kept in the StringIO yielded instead (empty when progress
    is silent): a side process's lines, shown by the process that started it (``show``)."""
    buffer = io.StringIO()
    token = _stream.set(buffer if _stream.get() is not None else None)
    try:
        yield buffer
    finally:
        _stream.reset(token)


def show(text: str) -> None:
    """Lines kept by ``held`` elsewhere, shown here."""
    stream = _stream.get()
    if stream is not None and text:
        stream.write(text)
        stream.flush()

"""Putting a finished output folder in place of an earlier one in one step, with no instant at which
neither is there.

On Linux ``renameat2(..., RENAME_EXCHANGE)`` swaps two paths atomically (glibc 2.28 and newer, most local
file systems). Where the call or the file system lacks it, the fallback is two renames (the earlier folder
aside, the new one in, the earlier one back if the second fails) with SIGINT and SIGTERM held back across
them, so an interrupt cannot fall between the two; only a SIGKILL or a power cut there would leave the
target missing, with the earlier output still beside it in the work folder.
"""
from __future__ import annotations

import contextlib
import ctypes
import errno
import os
import signal
import sys
import threading
from pathlib import Path

#: The signals a run handles (Ctrl-C, a timeout's or a scheduler's SIGTERM).
INTERRUPTS = {signal.SIGINT, signal.SIGTERM}
_AT_FDCWD = -100
_RENAME_EXCHANGE = 2


@contextlib.contextmanager
def interrupts_held():
    """SIGINT and SIGTERM held back inside the block and delivered when it ends (their handlers then run).
    Only the main thread may change what Python's handlers see; elsewhere the block runs as it is."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    previous = signal.pthread_sigmask(signal.SIG_BLOCK, INTERRUPTS)
    try:
        yield
    finally:
        signal.pthread_sigmask(signal.SIG_SETMASK, previous)


def _renameat2():
    """libc's renameat2, or None where there is none (not Linux, an old glibc, another libc)."""
    if not sys.platform.startswith("linux"):
        return None
    try:
        function = ctypes.CDLL(None, use_errno=True).renameat2
    except (OSError, AttributeError):
        return None
    function.argtypes = [ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint]
    function.restype = ctypes.c_int
    return function


_RENAMEAT2 = _renameat2()


def exchange(first: Path, second: Path) -> bool:
    """Swap two existing paths in one step; False (nothing done) where the system cannot, OSError on any other
    failure."""
    if _RENAMEAT2 is None:
        return False
    if _RENAMEAT2(_AT_FDCWD, os.fsencode(first), _AT_FDCWD, os.fsencode(second), _RENAME_EXCHANGE) == 0:
        return True
    code = ctypes.get_errno()
    if code in (errno.EINVAL, errno.ENOSYS, errno.ENOTSUP):      # the file system has no exchange
        return False
    raise OSError(code, os.strerror(code), str(second))


def put_in_place(new: Path, target: Path, aside: Path) -> None:
    """Make ``new`` the folder at ``target``; an earlier ``target`` ends at ``new``'s path (swapped) or at
    ``aside`` (two renames), both on the same file system, ``aside`` not yet there. Signals are held back
    across the step (``interrupts_held``)."""
    with interrupts_held():
        if not target.exists():
            new.replace(target)
            return
        if exchange(new, target):
            return
        target.replace(aside)
        try:
            new.replace(target)
        except OSError:
            aside.replace(target)
            raise

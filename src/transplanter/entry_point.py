"""The ``transplanter`` program's first lines: Ctrl-C and SIGTERM are handled before anything else is imported
(the command line's modules take a good part of a second to import), so an interrupt at any moment ends the program
with 130 and one line on stderr, never Python's KeyboardInterrupt traceback. Once ``cli`` is imported its
``console`` takes the signals over for the run."""
import os
import signal

#: The signals a run handles (``folder_swap.INTERRUPTS``, which is not imported here: it would import more).
_INTERRUPTS = (signal.SIGINT, signal.SIGTERM)


def _interrupted_while_starting(signum, frame) -> None:
    """Nothing has been read or written yet: say so in one line and end at once (no clean-up is owed)."""
    os.write(2, b"transplanter: interrupted while starting; nothing was read or written\n")
    os._exit(130)


def console() -> None:
    """The ``transplanter`` program: interrupts handled, then ``cli.console`` (which exits; ``typing.NoReturn`` is
    not named here, to import nothing more)."""
    for number in _INTERRUPTS:
        signal.signal(number, _interrupted_while_starting)
    from transplanter.cli import console as run

    run()

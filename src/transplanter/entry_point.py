"""The ``transplanter`` program's first lines: Ctrl-C and SIGTERM are handled before anything else is imported
(the command line's modules take a good part of a second to import), so an interrupt at any moment ends the program
with 130 and one line on stderr, never Python's KeyboardInterrupt traceback. Once ``cli`` is imported its
``console`` takes the signals over for the run."""
import os
import signal
import sys

#: The signals a run handles (``folder_swap.INTERRUPTS``, which is not imported here: it would import more).
_INTERRUPTS = (signal.SIGINT, signal.SIGTERM)


def _interrupted_while_starting(signum, frame) -> None:
    """Nothing has been read or written yet: say so in one line and end at once (no clean-up is owed)."""
    os.write(2, b"transplanter: interrupted while starting; nothing was read or written\n")
    os._exit(130)


def quiet_resource_tracker() -> None:
    """Keep multiprocessing's resource tracker from writing to the run's stderr. Ctrl-C in a study kills its
    worker processes, and the semaphores a killed worker made (its own process pools') are then removed by the
    tracker, a process of its own that warns about each "leaked" one when the program ends (four lines after
    "transplanter: interrupted", seen once in the study's Ctrl-C test). The tracker starts with this
    interpreter's warning options, so the option is added here, before any process is made; the removal itself
    is unchanged."""
    sys.warnoptions.append("ignore:resource_tracker:UserWarning")


def console() -> None:
    """The ``transplanter`` program: interrupts handled, then ``cli.console`` (which exits; ``typing.NoReturn`` is
    not named here, to import nothing more)."""
    for number in _INTERRUPTS:
        signal.signal(number, _interrupted_while_starting)
    quiet_resource_tracker()
    from transplanter.cli import console as run

    run()

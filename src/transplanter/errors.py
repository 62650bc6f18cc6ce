"""One exception family: the CLI prints these as one line and exits 2."""


class TransplanterError(Exception):
    """Base of every error the package raises on purpose."""


class ProblemError(TransplanterError):
    """Bad input: the message names the file, the field, the value and what was expected."""


class InfeasibleError(TransplanterError):
    """The input is well formed but no mechanism meets it: says which condition blocks."""


class SolverError(TransplanterError):
    """A numerical solve did not succeed: carries the solver's status."""

    def __init__(self, message: str, status: str):
        super().__init__(f"{message} (solver status: {status})")
        self.status = status


class TransplanterWarning(UserWarning):
    """Input that is legal but probably not what was meant (e.g. radians in a degree field)."""

"""transplanter: precise synthesis of seedling transplanting mechanisms.

Each mechanism is a subpackage with the same API: ``load_problem``/``parse_problem`` (TOML file or
dict, mm and degrees), ``synthesize`` (a result whose ``to_json()`` is the report) and
``draw_figures`` (matplotlib Figures); the ``transplanter`` command wraps them.

Importing the package imports nothing else (the program's entry point handles interrupts from its first line on,
``entry_point``); ``__version__`` is read from the installed distribution when first asked for.
"""


def __getattr__(name: str) -> str:
    """``__version__``: the installed distribution's version (one source of truth: pyproject.toml)."""
    if name != "__version__":
        raise AttributeError(f"module 'transplanter' has no attribute {name!r}")
    from importlib.metadata import version

    return version("transplanter")

"""transplanter: precise synthesis of seedling transplanting mechanisms.

Each mechanism is a subpackage with the same API: ``load_problem``/``parse_problem`` (TOML file or
dict, mm and degrees), ``synthesize`` (a result whose ``to_json()`` is the report) and
``draw_figures`` (matplotlib Figures); the ``transplanter`` command wraps them.
"""
from importlib.metadata import version

#: The installed distribution's version (one source of truth: pyproject.toml).
__version__ = version("transplanter")

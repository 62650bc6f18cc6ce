"""transplanter: precise synthesis of seedling transplanting mechanisms.

Each mechanism is a subpackage with the same API: ``load_problem``/``parse_problem`` (TOML file or
dict, mm and degrees) and ``synthesize``; the ``transplanter`` command wraps them.
"""

__version__ = "0.1.0"

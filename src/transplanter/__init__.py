"""transplanter: precise synthesis of seedling transplanting mechanisms.

Entry points: ``transplanter.problem.load_problem`` and ``transplanter.synthesis.synthesize``
(dyads through poses); the ``transplanter`` command wraps them.
"""

__version__ = "0.1.0"

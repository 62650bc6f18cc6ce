"""Symbolic derivations (sympy), the source of truth for src/transplanter/_generated/.

Run ``python -m derivations.build`` to regenerate, ``--check`` to detect drift.
sympy is needed here only, never by the installed package at run time.
"""

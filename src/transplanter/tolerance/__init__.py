"""Tolerance and sensitivity analysis of a built mechanism from exact derivatives.

A mechanism hands a ``ToleranceModel`` (its manufactured dimensions and its motion as a function of them,
through the generated closure); ``analyse`` gives the first-order bands from CasADi's Jacobian, a vectorised
Monte Carlo of the nonlinear mechanism, each dimension's share of the variance, the hard conditions'
violation fractions and a tolerance allocation.
"""
from transplanter.tolerance.analysis import ToleranceAnalysis, analyse
from transplanter.tolerance.dimensions import Dimension, ToleranceSettings, parse_tolerances
from transplanter.tolerance.model import ToleranceModel

__all__ = ["Dimension", "ToleranceAnalysis", "ToleranceModel", "ToleranceSettings", "analyse", "parse_tolerances"]

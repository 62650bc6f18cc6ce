"""The reverse train's four gears with whole teeth, cut and mesh-checked, made as the five-bar's train is
(``trains.toothed_train``): the module of ``[train] module``, its ``cutter`` (rack: a stage with a hollow goes
to the shaper, with the reason; a 16-tooth shaper), and the centre distances whole counts give.

Layout: without ``center_distances`` the carrier is bent as the five-bar's is (among whole counts at or above
their least, the least largest centre distance, then the least a1 + a2); centre distances that add up to the
carrier length s keep a straight carrier, others bend it (|a1 - a2| <= s <= a1 + a2); either way they must give
whole counts at the module, else the train keeps its pitch curves and the report says why there are no teeth.
"""
from __future__ import annotations

from transplanter.errors import InfeasibleError, ProblemError
from transplanter.reverse.problem import ReverseProblem
from transplanter.trains.gearing_fields import REVERSE_FIELDS
from transplanter.trains.planetary import RelativeMotion
from transplanter.trains.toothed_train import WHOLE, Gearing, ToothedTrain, design_toothed_train


def reverse_gearing(problem: ReverseProblem, carrier_length: float) -> Gearing:
    """The problem's module and centre distances as ``Gearing`` (layout in the module docstring)."""
    centers = problem.center_distances
    straight = centers is not None and abs(sum(centers) - carrier_length) <= WHOLE * carrier_length
    return Gearing(module=problem.module, cutter=problem.cutter, center_distances=centers, fields=REVERSE_FIELDS,
                   layout="straight" if straight else "bent")


def cut_train(problem: ReverseProblem, relative: RelativeMotion, carrier_length: float,
              exponent: float) -> tuple[ToothedTrain | None, str]:
    """The toothed train, or None and why there is none (given centre distances without whole counts, a module
    that gives too many teeth, a carrier too short for a tooth step, a cutter that cannot cut)."""
    try:
        return design_toothed_train(relative, carrier_length, reverse_gearing(problem, carrier_length),
                                    problem.source, exponent), ""
    except (ProblemError, InfeasibleError) as error:
        return None, f"no whole-tooth train: {error}"

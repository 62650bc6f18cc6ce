"""The one NLP layer: problems declared in named blocks (``layout``), solved by IPOPT with one option
set and one success rule (``ipopt``, the only module that calls ``casadi.nlpsol``), active bounds
reported by name (``active``), stalls stopped (``stall``) and whole-interval conditions held by the
exchange method (``exchange``)."""
from transplanter.solve.active import ActiveBound
from transplanter.solve.exchange import exchange, periodic_peaks
from transplanter.solve.ipopt import Solution, Solver
from transplanter.solve.layout import Bounds, NLPBuilder, NLPLayout
from transplanter.solve.stall import StallRule, relative_violation

__all__ = ["ActiveBound", "Bounds", "NLPBuilder", "NLPLayout", "Solution", "Solver", "StallRule", "exchange",
           "periodic_peaks", "relative_violation"]

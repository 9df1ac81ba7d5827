"""The periodic running half stride: flight, exact impact maps and stance (issue 23).

problem.py: phases of each strike, objectives, settings; collocation.py: the trapezoidal
transcription and the solve; layout.py: its bookkeeping (named blocks, rows, the raw solution);
guess.py: initial guesses; result.py: the `Stride`; checks.py: its checks against independent
methods; local.py: the optimum from its starts; search.py: the global search for the optimum
(its spend stated).
"""

from .collocation import StrideNLP
from .local import optimum
from .problem import OBJECTIVES, STRIKE_PHASES, StrideSettings
from .result import Stride, forward_checked, rank, summarise
from .search import global_optimum

__all__ = ["OBJECTIVES", "STRIKE_PHASES", "StrideSettings", "StrideNLP", "Stride", "forward_checked", "optimum", "rank",
           "summarise",
           "global_optimum"]

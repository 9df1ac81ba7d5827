"""The periodic running half stride: flight, exact impact maps and stance (issue 23).

problem.py: phases of each strike, objectives, settings; collocation.py: the trapezoidal
transcription and the solve; guess.py: initial guesses; result.py: the `Stride` and its checks.
"""

from .collocation import StrideNLP
from .problem import OBJECTIVES, STRIKE_PHASES, StrideSettings
from .result import Stride, optimum, summarise

__all__ = ["OBJECTIVES", "STRIKE_PHASES", "StrideSettings", "StrideNLP", "Stride", "optimum", "summarise"]

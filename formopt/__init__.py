"""formopt: the running form that wastes the least energy at foot strike.

A runner's stance leg as a planar multibody system in natural coordinates; the impact at
touchdown by projection onto the admissible motion space (after "Energy efficient walking and
running - impact dynamics based on varying geometric constraints"); every indicator a
differentiable CasADi function of the posture.

Layers, each importing only from those before it: mechanics (body, model, impact, landing),
optim (the posture NLP), io (scenes, motion capture, files), studies (compare, sweep,
bench), report (tables, figures), cli.
"""

from importlib.metadata import PackageNotFoundError, version

from .api import compare, impact, load, simulate, solve, stride, sweep
from .io.scene import Scene, SceneError
from .mechanics.impact import Impact, ImpactResult
from .mechanics.landing import Landing
from .optim.solution import Optimum

try:
    __version__ = version("formopt")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["load", "impact", "simulate", "solve", "sweep", "compare", "stride", "Scene", "SceneError",
           "Impact", "ImpactResult", "Landing", "Optimum", "__version__"]

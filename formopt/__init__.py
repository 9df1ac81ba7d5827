"""formopt: the running form that wastes the least energy at foot strike.

A runner's stance leg as a planar multibody system in natural coordinates; the impact at
touchdown by projection onto the admissible motion space (after "Energy efficient walking and
running - impact dynamics based on varying geometric constraints"); every indicator a
differentiable CasADi function of the posture.

Layers, each importing only from those before it: mechanics (body, model, impact, landing),
optim (the posture NLP), io (scenes, motion capture, files), studies (compare, sweep,
bench), report (tables, figures), cli.
"""

from importlib import import_module
from importlib.metadata import PackageNotFoundError, version
from typing import TYPE_CHECKING

# Public names and the module each lives in. They are imported on first use (PEP 562), so
# that `import formopt` (and the command line, which must answer Ctrl-C from its first
# instant) does not load CasADi, SciPy and Matplotlib before they are needed.
_PUBLIC = {"load": "api", "scenes": "api", "scene_path": "api", "impact": "api",
           "simulate": "api", "solve": "api", "sweep": "api", "compare": "api", "stride": "api",
           "Scene": "io.scene", "SceneError": "io.scene", "InputError": "mechanics.errors",
           "Body": "mechanics.body", "paper_body": "mechanics.body", "scaled_body": "mechanics.body",
           "Model": "mechanics.model", "build_model": "mechanics.model",
           "Impact": "mechanics.impact", "ImpactResult": "mechanics.impact",
           "impact_function": "mechanics.impact", "Landing": "mechanics.landing",
           "Optimum": "optim.solution", "Comparison": "studies.compare"}

if TYPE_CHECKING:
    from .api import compare, impact, load, scene_path, scenes, simulate, solve, stride, sweep
    from .io.scene import Scene, SceneError
    from .mechanics.body import Body, paper_body, scaled_body
    from .mechanics.errors import InputError
    from .mechanics.impact import Impact, ImpactResult, impact_function
    from .mechanics.landing import Landing
    from .mechanics.model import Model, build_model
    from .optim.solution import Optimum
    from .studies.compare import Comparison


def __getattr__(name: str):
    if name in _PUBLIC:
        value = getattr(import_module(f".{_PUBLIC[name]}", __name__), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'formopt' has no attribute {name!r}")


def __dir__():
    return sorted([*globals(), *_PUBLIC])


try:
    __version__ = version("formopt")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0+unknown"

__all__ = ["load", "scenes", "scene_path", "impact", "simulate", "solve", "sweep", "compare", "stride",
           "Scene", "SceneError", "InputError", "Body", "paper_body", "scaled_body", "Model",
           "build_model", "Impact", "ImpactResult", "impact_function", "Landing", "Optimum",
           "Comparison", "__version__"]

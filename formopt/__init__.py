"""formopt: the running form that wastes the least energy at foot strike.

A runner's stance leg as a planar multibody system in natural coordinates; the impact at
touchdown by projection; every indicator a differentiable CasADi function of the posture.
"""

from .body import Body, Segment, paper_body, scaled_body
from .impact import Impact, ImpactResult, angular_momentum_impact, impact, impact_function
from .model import STATE, STRIKES, Model, build_model
from .scene import Scene, SceneError, load

__all__ = ["Body", "Segment", "paper_body", "scaled_body", "Impact", "ImpactResult",
           "angular_momentum_impact", "impact", "impact_function", "STATE", "STRIKES", "Model",
           "build_model", "Scene", "SceneError", "load"]
__version__ = "0.1.0"

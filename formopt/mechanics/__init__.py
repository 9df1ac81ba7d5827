"""Mechanics: body data, the natural-coordinate model, the impact map, the landing.

Pure and in SI units: no scenes, no files. Everything above builds on these.
"""

# The public modules (imported on use: `from formopt.mechanics import impact`).
__all__ = ["body", "compiled", "contact", "dynamics", "errors", "impact", "integrators", "landing",
           "landing_function", "limits", "model", "muscles"]

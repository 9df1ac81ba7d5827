"""Mechanics: body data, the natural-coordinate model, the impact map, the landing.

Pure and in SI units: no scenes, no files. Everything above builds on these.
"""

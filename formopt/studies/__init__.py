"""Studies composed of the layers below: measured against optimal, sweeps, the bench."""

# The public modules (imported on use).
__all__ = ["bench", "compare", "optimum_map", "sweep"]

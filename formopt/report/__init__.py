"""Reports: text tables and Matplotlib figures of results (no printing, no backend)."""

# The public modules (imported on use).
__all__ = ["figures", "tables"]

"""Input and output at the boundary: scene files, motion capture, atomic output files."""

# The public modules (imported on use).
__all__ = ["export", "files", "markerset", "mocap", "muscle_table", "scene", "validate"]
